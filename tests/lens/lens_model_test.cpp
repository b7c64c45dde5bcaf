// The two lens models on regions of any shape: the paper's lift (a ridge magnifies across only)
// and the field (the lift read as log magnification, any shape magnified in every direction).

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>

#include "geolens/core/errors.h"
#include "geolens/geometry/grid.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_session.h"
#include "geolens/measure/distortion.h"
#include "lens/flatten.h"
#include "lens/lift.h"
#include "support/lens_options.h"

namespace geolens {
namespace {

using Points = std::vector<Eigen::Vector2d>;

// An L of 60 px wide arms in a 200 px box, and a five-pointed star of outer radius 120 px (inner
// vertices at 0.382 R), both around the centre of a 1024 px image: small enough that a 2.5x
// magnification fits in the image.
const Points kL = {{400, 400}, {460, 400}, {460, 540}, {600, 540}, {600, 600}, {400, 600}};

Points star() {
  Points p;
  for (int k = 0; k < 10; ++k) {
    const double r = k % 2 == 0 ? 120 : 0.382 * 120, a = M_PI / 2 + k * M_PI / 5;
    p.emplace_back(512 + r * std::cos(a), 512 - r * std::sin(a));
  }
  return p;
}

// Singular values (s1 >= s2) of the mean source -> screen Jacobian of the triangles whose
// source centroid lies within 12 px of `p`.
Eigen::Vector2d stretch_at(const WarpMesh& warp, const Eigen::Vector2d& p) {
  Eigen::Matrix2d sum = Eigen::Matrix2d::Zero();
  int count = 0;
  for (Eigen::Index f = 0; f < warp.F.rows(); ++f) {
    Eigen::Matrix2d S, T;
    for (int k = 0; k < 2; ++k) {
      S.col(k) = (warp.source.row(warp.F(f, k + 1)) - warp.source.row(warp.F(f, 0))).transpose();
      T.col(k) = (warp.screen.row(warp.F(f, k + 1)) - warp.screen.row(warp.F(f, 0))).transpose();
    }
    const Eigen::Vector2d centroid =
        warp.source.row(warp.F(f, 0)).transpose() + S.rowwise().sum() / 3;
    if ((centroid - p).norm() > 12) continue;
    sum += T * S.inverse();
    ++count;
  }
  return Eigen::JacobiSVD<Eigen::Matrix2d>(sum / count).singularValues();
}

// The acceptance case for shapes: on the 100 x 100 grid, an L and a star at zoom 2.5.
TEST(ShapeLens, LAndStarReachTheirZoomWithoutFlips) {
  const GeometricLens lens(1024, 1024, test::auto_model());
  for (const Points& polygon : {kL, star()}) {
    const LensResult r = lens.solve({Lens{Region::polygon(polygon), 2.5}});
    EXPECT_EQ(r.model, LensModel::kField);
    EXPECT_NEAR(r.zoom_measured[0] / 2.5, 1.0, 0.05) << polygon.size() << " vertices";
    const DistortionSummary d = summarize(measure_triangles(r.warp));
    EXPECT_EQ(d.flipped, 0) << polygon.size() << " vertices";
    EXPECT_LT(d.conformal_max, 5.0) << polygon.size() << " vertices";
  }
}

// Where the L's arms meet (its peak, (430, 570)): the field magnifies in every direction; the
// lift, two ridges each widening across, pinches it. Half-way along an arm both magnify
// mostly across (the context resists an arm growing longer far more than wider): with the
// field 2.7 across and 1.3 along at x = 430, y = 450.
TEST(ShapeLens, TheFieldMagnifiesTheLsJunctionInEveryDirectionTheLiftPinchesIt) {
  const Lens L{Region::polygon(kL), 2.5};
  LensOptions o = test::auto_model();
  o.model = LensModel::kField;
  const Eigen::Vector2d field =
      stretch_at(GeometricLens(1024, 1024, o).solve({L}).warp, {430, 570});
  o.model = LensModel::kLift;
  const Eigen::Vector2d lift = stretch_at(GeometricLens(1024, 1024, o).solve({L}).warp, {430, 570});
  EXPECT_GT(field(1), 2.0);
  EXPECT_LT(field(0) / field(1), 1.3);
  EXPECT_LT(lift(1), 1.6);
  EXPECT_GT(lift(0) / lift(1), 1.4);
}

TEST(ShapeLens, ShapesAndCirclesTogetherEachReachTheirZoom) {
  const GeometricLens lens(1024, 1024, test::auto_model());
  const std::vector<Lens> lenses = {Lens{Region::polygon(kL), 2.0},
                                    Lens{Region::circle({780, 260}, 110), 2.5},
                                    Lens{Region::circle({640, 640}, 90), 1.5}};  // overlaps the L
  const LensResult r = lens.solve(lenses);
  EXPECT_EQ(r.model, LensModel::kField);
  for (size_t k = 0; k < lenses.size(); ++k)
    EXPECT_NEAR(r.zoom_measured[k] / lenses[k].zoom, 1.0, 0.15) << "lens " << k;
  EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0);
}

TEST(ShapeLens, AutoPicksTheLiftForCirclesOnly) {
  const GeometricLens lens(1024, 1024, test::auto_model());
  EXPECT_EQ(lens.solve({Lens{Region::circle({512, 512}, 150)}}).model, LensModel::kLift);
  EXPECT_EQ(lens.solve({Lens{Region::polygon(star())}}).model, LensModel::kField);
  LensOptions o = test::auto_model();
  o.model = LensModel::kLift;
  EXPECT_EQ(GeometricLens(1024, 1024, o).solve({Lens{Region::polygon(star())}}).model,
            LensModel::kLift);
  for (const LensModel m : {LensModel::kLift, LensModel::kField, LensModel::kAuto})
    EXPECT_EQ(parse_lens_model(to_string(m)), m);
  EXPECT_THROW(parse_lens_model("ridge"), InvalidInput);
}

// A dragged polygon lens on the interactive path keeps its zoom and folds nothing.
TEST(ShapeLens, UpdateFollowsAMovingPolygon) {
  LensSession lens(1024, 1024, test::auto_model());
  for (int step = 0; step < 6; ++step) {
    Points moved = star();
    for (Eigen::Vector2d& p : moved) p.x() += 4.0 * step;
    const LensResult r = lens.update({Lens{Region::polygon(moved), 2.5}});
    EXPECT_NEAR(r.zoom_measured[0] / 2.5, 1.0, 0.03) << "step " << step;
    EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0) << "step " << step;
  }
}

// Scaled standard triangles with one scale everywhere and a free border: the minimum is the
// grid scaled, an exact similarity with zero energy.
TEST(ScaledStandard, AUniformScaleFlattensToTheScaledGrid) {
  const Grid grid = make_grid(300, 200, 31);
  const Lifted flat = lift(grid.V, {}, {});
  FlattenOptions o;
  o.standard = Standard::kScaled;
  o.boundary = Boundary::kFree;
  o.tolerance = 1e-12;
  const Eigen::VectorXd log_scale = Eigen::VectorXd::Constant(grid.V.rows(), std::log(1.5));
  const FlattenResult r = flatten(flat.V, grid.F, flat.level, grid.sides, o, log_scale);
  const Eigen::MatrixX2d expected =
      (1.5 * (grid.V.rowwise() - grid.V.row(0))).rowwise() + grid.V.row(0);
  EXPECT_LT((r.X - expected).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT(r.energy.back(), 1e-12 * r.energy.front());
  EXPECT_THROW(flatten(flat.V, grid.F, flat.level, grid.sides, o), InvalidInput);  // no scales
}

}  // namespace
}  // namespace geolens
