#include "geometry/mask_contour.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "geolens/core/errors.h"

namespace geolens {
namespace {

using Loop = std::vector<Eigen::Vector2d>;

// Nodes at (i, j) (origin 0) inside when `in` says so.
template <typename In>
std::vector<uint8_t> raster(int width, int height, In in) {
  std::vector<uint8_t> out(size_t(width) * height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) out[size_t(j) * width + i] = uint8_t(in(i, j));
  return out;
}

double signed_area(const Loop& loop) {
  double twice = 0;
  for (size_t k = 0; k < loop.size(); ++k) {
    const Eigen::Vector2d &a = loop[k], &b = loop[(k + 1) % loop.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return twice / 2;
}

TEST(MaskContours, DiscIsOneSmoothLoopOnItsRim) {
  const double r = 30;
  const Eigen::Vector2d c(40.3, 37.8);
  const std::vector<uint8_t> in =
      raster(80, 80, [&](int i, int j) { return (Eigen::Vector2d(i, j) - c).norm() <= r; });
  const std::vector<Loop> loops = mask_contours(in, 80, 80, Eigen::Vector2d::Zero());
  ASSERT_EQ(loops.size(), 1u);
  // Within half a node of the circle: the staircase of nodes smoothed, then simplified.
  for (const Eigen::Vector2d& p : loops[0]) EXPECT_NEAR((p - c).norm(), r, 0.5) << p.transpose();
  // Counter-clockwise on the screen (y down): a negative shoelace sum.
  EXPECT_NEAR(-signed_area(loops[0]), M_PI * r * r, 0.02 * M_PI * r * r);
  // Simplified: far fewer vertices than the ~190 nodes along the rim, no two closer than a node.
  EXPECT_LT(loops[0].size(), 80u);
}

TEST(MaskContours, StraightSidesLieOnThePixelEdgesAndTheOriginShiftsThem) {
  // Nodes 10..29 x 5..14 in: with nodes at pixel centres (origin 0.5), pixels 10..29 x 5..14,
  // whose squares end at x = 10 and 30, y = 5 and 15.
  const std::vector<uint8_t> in =
      raster(40, 20, [](int i, int j) { return i >= 10 && i < 30 && j >= 5 && j < 15; });
  const std::vector<Loop> loops = mask_contours(in, 40, 20, Eigen::Vector2d(0.5, 0.5));
  ASSERT_EQ(loops.size(), 1u);
  for (const Eigen::Vector2d& p : loops[0]) {
    const double dx = std::min(std::abs(p.x() - 10), std::abs(p.x() - 30));
    const double dy = std::min(std::abs(p.y() - 5), std::abs(p.y() - 15));
    EXPECT_TRUE(p.x() >= 10 - 1e-9 && p.x() <= 30 + 1e-9 && p.y() >= 5 - 1e-9 && p.y() <= 15 + 1e-9)
        << p.transpose();
    // Away from the (rounded) corners, on a side's line.
    if (std::max(dx, dy) > 2) EXPECT_LT(std::min(dx, dy), 1e-9) << p.transpose();
  }
  // The corners rounded by under a pixel: the area within 5 % of the 200 pixels.
  EXPECT_NEAR(-signed_area(loops[0]), 200, 10);
}

TEST(MaskContours, HoleHasItsOwnLoopTurningTheOtherWay) {
  const Eigen::Vector2d c(30, 30);
  const std::vector<uint8_t> in = raster(60, 60, [&](int i, int j) {
    const double d = (Eigen::Vector2d(i, j) - c).norm();
    return d <= 25 && d >= 12;
  });
  const std::vector<Loop> loops = mask_contours(in, 60, 60, Eigen::Vector2d::Zero());
  ASSERT_EQ(loops.size(), 2u);
  const double a0 = signed_area(loops[0]), a1 = signed_area(loops[1]);
  EXPECT_LT(a0, 0);  // the outer rim's cell comes first in row-major order
  EXPECT_GT(a1, 0);
  EXPECT_NEAR(-(a0 + a1), M_PI * (25 * 25 - 12 * 12), 0.03 * M_PI * (25 * 25 - 12 * 12));
}

TEST(MaskContours, ThinLinesVanishAndBlobsApartHaveALoopEach) {
  // A line one node wide is below the smoothing's level 1/2 (6 / 16 at most); two squares apart.
  const std::vector<uint8_t> in = raster(50, 20, [](int i, int j) {
    return j == 3 || (j >= 8 && j < 16 && ((i >= 5 && i < 15) || (i >= 30 && i < 40)));
  });
  const std::vector<Loop> loops = mask_contours(in, 50, 20, Eigen::Vector2d::Zero());
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_LT(loops[0][0].x(), loops[1][0].x());
}

TEST(MaskContours, RejectsABadRasterOrTolerance) {
  const std::vector<uint8_t> in(12, 1);
  for (const auto& call : std::vector<std::function<void()>>{
           [&] { mask_contours(in, 3, 5, Eigen::Vector2d::Zero()); },
           [&] { mask_contours(in, 0, 12, Eigen::Vector2d::Zero()); },
           [&] { mask_contours(in, 3, 4, Eigen::Vector2d::Zero(), -1); },
           [&] { mask_contours(in, 3, 4, Eigen::Vector2d::Zero(), NAN); }}) {
    try {
      call();
      ADD_FAILURE() << "expected InvalidInput";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()).rfind("mask_contours: ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace geolens
