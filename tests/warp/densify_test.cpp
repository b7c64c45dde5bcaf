// Densifying a polyline: its vertices kept bit for bit, every segment short enough, the new
// vertices evenly on the old segments.

#include "warp/densify.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geolens/core/errors.h"

namespace geolens {
namespace {

TEST(Densify, KeepsTheVerticesAndShortensEverySegment) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-100, 900);
  Eigen::MatrixX2d path(12, 2);
  for (Eigen::Index i = 0; i < path.rows(); ++i) path.row(i) << u(rng), u(rng);
  path.row(5) = path.row(4);  // a zero-length segment
  for (const double max_segment : {0.7, 3.0, 50.0}) {
    SCOPED_TRACE(max_segment);
    const Eigen::MatrixX2d out = densify(path, max_segment);
    Eigen::Index next = 0;
    for (Eigen::Index i = 0; i + 1 < path.rows(); ++i) {
      const Eigen::RowVector2d a = path.row(i), b = path.row(i + 1);
      const double length = (b - a).norm();
      const Eigen::Index n =
          std::max<Eigen::Index>(Eigen::Index(std::ceil(length / max_segment)), 1);
      EXPECT_EQ(out.row(next), a);  // exactly
      for (Eigen::Index k = 1; k <= n; ++k) {
        const double step = (out.row(next + k) - out.row(next + k - 1)).norm();
        EXPECT_LE(step, max_segment * (1 + 1e-12));
        EXPECT_NEAR(step, length / double(n), 1e-9);
        // On the segment.
        const Eigen::RowVector2d d = out.row(next + k) - a;
        EXPECT_NEAR(d.x() * (b - a).y() - d.y() * (b - a).x(), 0, 1e-9 * (1 + length * length));
      }
      next += n;
    }
    EXPECT_EQ(out.row(next), path.row(path.rows() - 1));
    EXPECT_EQ(next + 1, out.rows());
  }
}

TEST(Densify, AClosedRingStaysClosedAndInfinityChangesNothing) {
  Eigen::MatrixX2d ring(5, 2);
  ring << 0.1, 0.2, 10.3, 0.2, 10.3, 7.7, 0.1, 7.7, 0.1, 0.2;
  const Eigen::MatrixX2d out = densify(ring, 1.0);
  EXPECT_EQ(out.row(0), out.row(out.rows() - 1));
  EXPECT_EQ(out.rows(), 1 + 11 + 8 + 11 + 8);
  EXPECT_EQ(densify(ring, std::numeric_limits<double>::infinity()), ring);
  EXPECT_EQ(densify(Eigen::RowVector2d(1, 2), 0.5), Eigen::RowVector2d(1, 2));
  EXPECT_EQ(densify(Eigen::MatrixX2d(0, 2), 0.5).rows(), 0);
}

TEST(Densify, RefusesBadInput) {
  const Eigen::MatrixX2d line = (Eigen::MatrixX2d(2, 2) << 0, 0, 1e9, 0).finished();
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(densify(line, bad), InvalidInput) << bad;
  EXPECT_THROW(densify(line, 1e-3), InvalidInput);  // 1e12 vertices
  Eigen::MatrixX2d not_finite = line;
  not_finite(1, 1) = std::numeric_limits<double>::infinity();
  try {
    densify(not_finite, 1);
    ADD_FAILURE();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("densify: path row 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace geolens
