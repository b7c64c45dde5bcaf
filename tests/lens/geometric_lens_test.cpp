#include "geolens/lens/geometric_lens.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>

#include "geolens/core/errors.h"
#include "geolens/measure/distortion.h"
#include "support/lens_options.h"

namespace geolens {
namespace {

Lens circle(double x, double y, double radius, double zoom, Profile profile) {
  return Lens{Region::circle({x, y}, radius), zoom, profile};
}

// The acceptance case: 1024 x 1024, r = 150 at the centre, default options.
class ZoomTest : public ::testing::TestWithParam<std::tuple<Profile, double>> {};

TEST_P(ZoomTest, MeasuredZoomIsWithinTenPercentWithoutFlips) {
  const auto [profile, zoom] = GetParam();
  const GeometricLens lens(1024, 1024, test::auto_model());
  const LensResult r = lens.solve({circle(512, 512, 150, zoom, profile)});
  EXPECT_NEAR(r.zoom_measured[0] / zoom, 1.0, 0.10);
  EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0);
  EXPECT_TRUE(r.flattening.converged);
  EXPECT_LE(r.flattening.iterations, 10);
}

INSTANTIATE_TEST_SUITE_P(ProfilesAndZooms, ZoomTest,
                         ::testing::Combine(::testing::Values(Profile::kGaussian, Profile::kSphere,
                                                              Profile::kMesa),
                                            ::testing::Values(1.5, 2.0, 3.0)));

TEST(GeometricLens, ZoomOneIsTheIdentity) {
  const GeometricLens lens(300, 200, test::auto_model());
  const LensResult r = lens.solve({circle(150, 100, 60, 1.0, Profile::kGaussian)});
  EXPECT_EQ(r.lift_heights_px.at(0), 0.0);
  EXPECT_LT((r.warp.source - lens.grid().V).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((r.warp.screen - lens.grid().V).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(r.zoom_measured[0], 1.0, 1e-9);
}

// Mirror-symmetric grid: an even number of cells per side (mesh 41 -> 40 cells).
TEST(GeometricLens, CentredLensOnASquareImageGivesASymmetricWarp) {
  LensOptions options = test::auto_model();
  options.mesh = 41;
  const GeometricLens lens(400, 400, options);
  const LensResult r = lens.solve({circle(200, 200, 80, 2.0, Profile::kGaussian)});
  const Grid& g = lens.grid();
  double asymmetry = 0, moved = 0;
  for (int row = 0; row < g.rows; ++row) {
    for (int col = 0; col < g.columns; ++col) {
      const int i = row * g.columns + col;
      const int mirror_x = row * g.columns + (g.columns - 1 - col);
      const int mirror_y = (g.rows - 1 - row) * g.columns + col;
      const int transpose = col * g.columns + row;
      const Eigen::Vector2d p = r.warp.screen.row(i);
      const Eigen::Vector2d px = r.warp.screen.row(mirror_x), py = r.warp.screen.row(mirror_y),
                            pt = r.warp.screen.row(transpose);
      asymmetry = std::max({asymmetry, (Eigen::Vector2d(400 - px.x(), px.y()) - p).norm(),
                            (Eigen::Vector2d(py.x(), 400 - py.y()) - p).norm(),
                            (Eigen::Vector2d(pt.y(), pt.x()) - p).norm()});
      moved = std::max(moved, (p - g.V.row(i).transpose()).norm());
    }
  }
  EXPECT_GT(moved, 5.0);
  EXPECT_LT(asymmetry, 1e-6 * 400);
}

TEST(GeometricLens, RejectsInvalidLenses) {
  const GeometricLens lens(100, 100, test::auto_model());
  EXPECT_THROW(lens.solve({circle(50, 50, 0, 2, Profile::kGaussian)}), InvalidInput);
  EXPECT_THROW(lens.solve({circle(50, 50, -3, 2, Profile::kGaussian)}), InvalidInput);
  EXPECT_THROW(lens.solve({circle(150, 50, 10, 2, Profile::kGaussian)}), InvalidInput);
  EXPECT_THROW(lens.solve({circle(50, 50, 10, 9, Profile::kGaussian)}), InvalidInput);
  EXPECT_THROW(lens.solve({circle(50, 50, 10, 0.5, Profile::kGaussian)}), InvalidInput);
  EXPECT_THROW(lens.solve({circle(50, 50, std::nan(""), 2, Profile::kGaussian)}), InvalidInput);
  LensOptions options = test::auto_model();
  options.mesh = 3;
  EXPECT_THROW(GeometricLens(100, 100, options), InvalidInput);
  options.mesh = 1001;
  EXPECT_THROW(GeometricLens(100, 100, options), InvalidInput);
  // One parameter per lens: a LensResult's heights of another set of lenses are refused.
  const std::vector<Lens> two = {circle(30, 50, 10, 2, Profile::kGaussian),
                                 circle(70, 50, 10, 2, Profile::kGaussian)};
  EXPECT_THROW(lens.solve_with_heights(two, {20.0}), InvalidInput);
  EXPECT_NO_THROW(lens.solve_with_heights(two, {20.0, 20.0}));
}

}  // namespace
}  // namespace geolens

namespace geolens {
namespace {

// Local extent: the patch around the lens is solved, the rest of the image is the identity, and
// the warp still covers the image exactly once.
TEST(GeometricLens, LocalExtentSolvesAPatchAndLeavesTheRestAlone) {
  LensOptions options = test::auto_model();
  options.mesh = 50;
  options.extent = Extent::kLocal;
  options.extent_factor = 2.0;
  const GeometricLens lens(2000, 1500, options);
  const LensResult r = lens.solve({Lens{Region::circle({700, 600}, 100), 2.0}});
  EXPECT_NEAR(r.zoom_measured[0], 2.0, 0.1);
  EXPECT_TRUE(
      r.box.isApprox(Eigen::AlignedBox2d(Eigen::Vector2d(500, 400), Eigen::Vector2d(900, 800))));
  const TriangleDistortion d = measure_triangles(r.warp);
  EXPECT_EQ(summarize(d).flipped, 0);
  EXPECT_NEAR(d.source_area.sum(), 2000.0 * 1500.0, 1e-6);
  // Vertices on and outside the patch border keep their place.
  for (Eigen::Index i = 0; i < r.warp.source.rows(); ++i) {
    const Eigen::Vector2d p = r.warp.source.row(i);
    if (!r.box.contains(p) || i >= r.mesh.V.rows() || r.mesh.sides[size_t(i)] != 0)
      EXPECT_LT((r.warp.screen.row(i) - r.warp.source.row(i)).norm(), 1e-9) << i;
  }
  // A lens near the image corner clips the patch; the frame skips the empty trapezoids.
  const LensResult corner = lens.solve({Lens{Region::circle({120, 100}, 90), 2.0}});
  const TriangleDistortion dc = measure_triangles(corner.warp);
  EXPECT_EQ(summarize(dc).flipped, 0);
  EXPECT_NEAR(dc.source_area.sum(), 2000.0 * 1500.0, 1e-6);
}

}  // namespace
}  // namespace geolens

namespace geolens {
namespace {

// Several lenses in one solve, each calibrated to its own zoom; overlapping ones combine by max
// of height without a fold.
TEST(GeometricLens, SeveralLensesEachReachTheirZoom) {
  const GeometricLens lens(1024, 1024, test::auto_model());
  const std::vector<std::vector<Lens>> cases = {
      {Lens{Region::circle({300, 300}, 110), 2.0}, Lens{Region::circle({720, 700}, 130), 3.0}},
      {Lens{Region::circle({450, 500}, 120), 2.0}, Lens{Region::circle({600, 520}, 120), 2.5}},
      {Lens{Region::circle({200, 200}, 90), 1.5}, Lens{Region::circle({800, 200}, 90), 2.0},
       Lens{Region::circle({512, 512}, 110), 2.5}, Lens{Region::circle({200, 800}, 90), 3.0},
       Lens{Region::circle({820, 820}, 90), 2.0, Profile::kMesa}}};
  for (const std::vector<Lens>& lenses : cases) {
    const LensResult r = lens.solve(lenses);
    for (size_t k = 0; k < lenses.size(); ++k)
      EXPECT_NEAR(r.zoom_measured[k] / lenses[k].zoom, 1.0, 0.15)
          << lenses.size() << " lenses, lens " << k;
    EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0) << lenses.size() << " lenses";
  }
}

// The thread count changes no bit of a solve: every parallel loop writes its own range and
// reduces in a fixed order. At mesh 100 the per-vertex and per-triangle loops (10^4 - 2 10^4
// items) do split over two threads. The focus model (two lenses), the lift model (global) and
// the field model (a polygon).
TEST(GeometricLens, SolvesBitIdenticallyOnOneAndOnTwoThreads) {
  const Region triangle = Region::polygon({{300, 250}, {620, 300}, {420, 560}});
  const std::vector<std::pair<LensOptions, std::vector<Lens>>> cases = {
      {LensOptions{}, {Lens{triangle, 2.5}, Lens{Region::circle({700, 420}, 70), 2.0}}},
      {test::auto_model(), {Lens{Region::circle({500, 400}, 120), 2.0}}},
      {test::auto_model(), {Lens{triangle, 2.0}}}};
  for (const auto& [options, lenses] : cases) {
    LensOptions one = options, two = options;
    one.flatten.threads = 1;
    two.flatten.threads = 2;
    const LensResult a = GeometricLens(1000, 800, one).solve(lenses);
    const LensResult b = GeometricLens(1000, 800, two).solve(lenses);
    const std::string model = to_string(a.model);
    // The focus lens's start already meets its bounds; the others iterate.
    if (a.model != LensModel::kFocus) EXPECT_GT(a.flattening.iterations, 0) << model;
    EXPECT_EQ(a.warp.F, b.warp.F) << model;
    EXPECT_EQ(a.warp.source, b.warp.source) << model;
    EXPECT_EQ(a.warp.screen, b.warp.screen) << model;
    EXPECT_EQ(a.flattening.energy, b.flattening.energy) << model;
    EXPECT_EQ(a.lift_heights_px, b.lift_heights_px) << model;
    EXPECT_EQ(a.focus_log_zooms, b.focus_log_zooms) << model;
    EXPECT_EQ(a.zoom_measured, b.zoom_measured) << model;
  }
  LensOptions negative;
  negative.flatten.threads = -1;
  EXPECT_THROW(GeometricLens(1000, 800, negative), InvalidInput);
}

}  // namespace
}  // namespace geolens
