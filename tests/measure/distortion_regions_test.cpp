// Region statistics and the Eq. 7 energy: zones of the right size, exact figures for affine
// warps, the occluded area of a warp pushed off screen, and Eq. 7 against a direct edge sum.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <numbers>
#include <random>

#include "geolens/core/errors.h"
#include "geolens/geometry/grid.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/measure/distortion.h"

namespace geolens {
namespace {

constexpr double kPi = std::numbers::pi;

WarpMesh identity_warp(const Eigen::MatrixX2d& V, const Eigen::MatrixX3i& F, int w, int h) {
  return WarpMesh{F, V, V, w, h};
}

// The grid warped by screen = A (p - c) + c + t.
WarpMesh affine_warp(const Grid& grid, const Eigen::Matrix2d& A, const Eigen::Vector2d& c,
                     const Eigen::Vector2d& t, int w, int h) {
  WarpMesh warp = identity_warp(grid.V, grid.F, w, h);
  for (Eigen::Index i = 0; i < grid.V.rows(); ++i)
    warp.screen.row(i) = (A * (grid.V.row(i).transpose() - c) + c + t).transpose();
  return warp;
}

// A warp with a triangle squashed to a sliver is flagged degenerate (its figures say how badly it
// collapsed, not what a picture shows); a mild one is not.
TEST(DistortionSummary, ACollapsedTriangleMakesTheFiguresDegenerate) {
  WarpMesh warp;
  warp.source.resize(3, 2);
  warp.source << 0, 0, 10, 0, 0, 10;
  warp.F.resize(1, 3);
  warp.F << 0, 1, 2;
  warp.screen = warp.source;
  warp.screen(2, 1) = 1e-12;  // squashed onto the x axis, still counter-clockwise
  warp.screen_width = warp.screen_height = 10;
  EXPECT_TRUE(summarize(measure_triangles(warp)).degenerate());
  warp.screen(2, 1) = 5;  // half as tall: conformal 1
  const DistortionSummary mild = summarize(measure_triangles(warp));
  EXPECT_NEAR(mild.conformal_max, 1, 1e-9);
  EXPECT_FALSE(mild.degenerate());
}

TEST(DistortionRegions, ZonesHaveTheAreasOfTheirDisks) {
  const CircleLens lens{{300, 260}, 120, 2};
  EXPECT_DOUBLE_EQ(focus_radius(lens), 30);
  const PlanarMesh mesh =
      ringed_grid(600, 500, 150, {{lens.center, focus_radius(lens)}, {lens.center, lens.radius}});
  const WarpMesh warp = identity_warp(mesh.V, mesh.F, 600, 500);
  const RegionStatistics r = measure_regions(warp, measure_triangles(warp), {lens}, 600, 500);
  const double focus = kPi * 30 * 30, disk = kPi * 120 * 120;
  EXPECT_NEAR(r.focus.area / focus, 1, 0.005);
  EXPECT_NEAR(r.transition.area / (disk - focus), 1, 0.002);
  EXPECT_NEAR(r.context.area / (600.0 * 500 - disk), 1, 0.001);
  EXPECT_NEAR(r.overall.area, 600.0 * 500, 1e-6);
  // The identity: nothing distorted, magnified, hidden or flipped.
  for (const ZoneStatistics* z : {&r.focus, &r.transition, &r.context, &r.overall}) {
    EXPECT_GT(z->triangles, 0);
    EXPECT_LT(z->conformal_max, 1e-9);
    EXPECT_NEAR(z->magnification_min, 1, 1e-9);
    EXPECT_NEAR(z->magnification_max, 1, 1e-9);
    EXPECT_LT(z->area_distortion_mean, 1e-9);
    EXPECT_EQ(z->flipped, 0);
  }
  EXPECT_NEAR(r.occluded_area, 0, 1e-6);
  EXPECT_NEAR(r.focus_uniformity, 1, 1e-9);
}

TEST(DistortionRegions, NearestLensDecidesAndEveryTriangleHasOneZone) {
  const Grid grid = make_grid(400, 200, 81);
  const WarpMesh warp = identity_warp(grid.V, grid.F, 400, 200);
  const std::vector<CircleLens> lenses = {{{100, 100}, 60, 1}, {{300, 100}, 60, 3}};
  const std::vector<TriangleZone> zones = classify_triangles(warp, lenses);
  ASSERT_EQ(zones.size(), size_t(grid.F.rows()));
  for (Eigen::Index f = 0; f < grid.F.rows(); ++f) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (int k = 0; k < 3; ++k) mean += grid.V.row(grid.F(f, k)).transpose() / 3;
    // Far from both circles the zone is clear from the centroid.
    const double d1 = (mean - lenses[0].center).norm(), d2 = (mean - lenses[1].center).norm();
    if (d1 < 25) EXPECT_EQ(zones[size_t(f)].zone, Zone::kFocus);  // focus radius 30
    if (d1 < 55) EXPECT_EQ(zones[size_t(f)].lens, 0);
    if (d2 > 15 && d2 < 55) EXPECT_EQ(zones[size_t(f)].zone, Zone::kTransition);  // focus 10
    if (d2 < 55) EXPECT_EQ(zones[size_t(f)].lens, 1);
    if (d1 > 65 && d2 > 65) EXPECT_EQ(zones[size_t(f)].zone, Zone::kContext);
  }
  EXPECT_EQ(to_string(Zone::kFocus), "focus");
  EXPECT_EQ(to_string(Zone::kTransition), "transition");
  EXPECT_EQ(to_string(Zone::kContext), "context");
}

TEST(DistortionRegions, SimilarityHasNoShapeDistortionAndHidesWhatLeavesTheScreen) {
  // Scaled 2x about the image centre with a rotation: shape kept, area x4, and only the middle
  // quarter of the source (rotated by 30 degrees, so a little less) stays on screen.
  const Grid grid = make_grid(400, 400, 201);
  const Eigen::Matrix2d A = 2 * Eigen::Rotation2Dd(kPi / 6).toRotationMatrix();
  const WarpMesh warp = affine_warp(grid, A, {200, 200}, Eigen::Vector2d::Zero(), 400, 400);
  const RegionStatistics r =
      measure_regions(warp, measure_triangles(warp), {{{200, 200}, 50, 2}}, 400, 400);
  EXPECT_LT(r.overall.conformal_max, 1e-9);
  EXPECT_NEAR(r.overall.magnification_min, 2, 1e-9);
  EXPECT_NEAR(r.overall.magnification_max, 2, 1e-9);
  EXPECT_NEAR(r.overall.area_distortion_mean, 3, 1e-9);
  // Visible source: the screen square mapped back, a 200 x 200 square rotated by 30 degrees,
  // clipped to the source square (all of it fits): 40000 of 160000 pixels^2.
  EXPECT_NEAR(r.occluded_percent, 75, 0.5);
}

TEST(DistortionRegions, StretchHasItsAnalyticDistortion) {
  const Grid grid = make_grid(300, 200, 61);
  Eigen::Matrix2d A;
  A << 3, 0, 0, 1.5;  // s1 / s2 - 1 = 1, area x 4.5
  const WarpMesh warp =
      affine_warp(grid, A, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), 900, 300);
  const RegionStatistics r =
      measure_regions(warp, measure_triangles(warp), {{{150, 100}, 40, 1.5}}, 300, 200);
  for (const ZoneStatistics* z : {&r.focus, &r.transition, &r.context}) {
    EXPECT_NEAR(z->conformal_mean, 1, 1e-9);
    EXPECT_NEAR(z->conformal_max, 1, 1e-9);
    EXPECT_NEAR(z->area_distortion_mean, 3.5, 1e-9);
  }
  EXPECT_NEAR(r.occluded_area, 0, 1e-6);
}

TEST(DistortionRegions, FlippedTrianglesAreCountedNotMeasured) {
  const Grid grid = make_grid(100, 100, 11);
  Eigen::Matrix2d mirror;
  mirror << -1, 0, 0, 1;
  const WarpMesh warp = affine_warp(grid, mirror, {50, 50}, Eigen::Vector2d::Zero(), 100, 100);
  const RegionStatistics r =
      measure_regions(warp, measure_triangles(warp), {{{50, 50}, 30, 1}}, 100, 100);
  EXPECT_EQ(r.overall.flipped, grid.F.rows());
  EXPECT_EQ(r.overall.triangles, 0);
  EXPECT_EQ(r.overall.conformal_max, 0);
  EXPECT_EQ(r.focus.flipped + r.transition.flipped + r.context.flipped, grid.F.rows());
}

TEST(DistortionRegions, RejectsBadInput) {
  const Grid grid = make_grid(100, 100, 11);
  const WarpMesh warp = identity_warp(grid.V, grid.F, 100, 100);
  const TriangleDistortion m = measure_triangles(warp);
  EXPECT_THROW(measure_regions(warp, m, {}, 100, 100), InvalidInput);
  EXPECT_THROW(measure_regions(warp, m, {{{50, 50}, 0, 2}}, 100, 100), InvalidInput);
  EXPECT_THROW(measure_regions(warp, m, {{{50, 50}, 10, 0.5}}, 100, 100), InvalidInput);
  EXPECT_THROW(measure_regions(warp, m, {{{50, NAN}, 10, 2}}, 100, 100), InvalidInput);
  EXPECT_THROW(measure_regions(warp, m, {{{50, 50}, 10, 2}}, 0, 100), InvalidInput);
  TriangleDistortion short_measures = m;
  short_measures.conformal.resize(3);
  EXPECT_THROW(measure_regions(warp, short_measures, {{{50, 50}, 10, 2}}, 100, 100), InvalidInput);
}

// Direct Eq. 7 sum: sum over the three edges of cot(opposite angle in the standard triangle) *
// ||e - R e_std||^2, R the rotation of the polar decomposition (Eigen's SVD) of the Jacobian.
double eq7_direct(const Eigen::Vector3d v[3], const Eigen::Vector2d x[3]) {
  const Eigen::Vector3d a = v[1] - v[0], b = v[2] - v[0];
  const Eigen::Vector3d n = a.cross(b).normalized(), ex = a.normalized(), ey = n.cross(ex);
  Eigen::Vector2d s[3];
  for (int k = 0; k < 3; ++k) s[k] = {(v[k] - v[0]).dot(ex), (v[k] - v[0]).dot(ey)};
  Eigen::Matrix2d S, X;
  S << s[1] - s[0], s[2] - s[0];
  X << x[1] - x[0], x[2] - x[0];
  const Eigen::Matrix2d J = X * S.inverse();
  Eigen::JacobiSVD<Eigen::Matrix2d> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix2d D = Eigen::Matrix2d::Identity();
  D(1, 1) = (svd.matrixU() * svd.matrixV().transpose()).determinant();
  const Eigen::Matrix2d R = svd.matrixU() * D * svd.matrixV().transpose();
  double e = 0;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;  // edge opposite corner k
    const Eigen::Vector2d u = s[i] - s[k], w = s[j] - s[k];
    const double cot = u.dot(w) / std::abs(u.x() * w.y() - u.y() * w.x());
    e += cot * ((x[j] - x[i]) - R * (s[j] - s[i])).squaredNorm();
  }
  return e;
}

TEST(DistortionRegions, Eq7MatchesADirectEdgeSum) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-10, 10);
  Eigen::MatrixX3d V3(60, 3);
  Eigen::MatrixX2d X(60, 2);
  Eigen::MatrixX3i F(20, 3);
  for (int f = 0; f < 20; ++f) {
    for (int k = 0; k < 3; ++k) {
      V3.row(3 * f + k) << coordinate(random), coordinate(random), coordinate(random);
      X.row(3 * f + k) << coordinate(random), coordinate(random);
    }
    // Keep the flat triangle's orientation positive (the standard triangle's always is), so the
    // closest rotation is the proper polar factor in both computations.
    Eigen::Matrix2d E;
    E << (X.row(3 * f + 1) - X.row(3 * f)).transpose(),
        (X.row(3 * f + 2) - X.row(3 * f)).transpose();
    if (E.determinant() < 0) {
      X.row(3 * f + 1).swap(X.row(3 * f + 2));
      V3.row(3 * f + 1).swap(V3.row(3 * f + 2));
    }
    F.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
  }
  const Eigen::VectorXd energy = eq7_energy(V3, F, X);
  for (int f = 0; f < 20; ++f) {
    Eigen::Vector3d v[3];
    Eigen::Vector2d x[3];
    for (int k = 0; k < 3; ++k) {
      v[k] = V3.row(F(f, k)).transpose();
      x[k] = X.row(F(f, k)).transpose();
    }
    EXPECT_NEAR(energy(f), eq7_direct(v, x), 1e-9 * (1 + energy(f))) << f;
  }
}

TEST(DistortionRegions, Eq7IsZeroForRigidAndKnownForScale) {
  const Grid grid = make_grid(50, 40, 11);
  Eigen::MatrixX3d V3 = Eigen::MatrixX3d::Zero(grid.V.rows(), 3);
  V3.leftCols<2>() = grid.V;
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(0.7).toRotationMatrix();
  const Eigen::MatrixX2d rigid = (grid.V * R.transpose()).rowwise() + Eigen::RowVector2d(5, -3);
  EXPECT_LT(eq7_energy(V3, grid.F, rigid).cwiseAbs().maxCoeff(), 1e-9);
  // Scale 1.5: each triangle 2 A (0.5^2 + 0.5^2) = A.
  const Eigen::VectorXd scaled = eq7_energy(V3, grid.F, 1.5 * grid.V);
  EXPECT_NEAR(scaled.sum(), 50.0 * 40.0, 1e-6);
  EXPECT_THROW(eq7_energy(V3, grid.F, grid.V.topRows(3)), InvalidInput);
}

}  // namespace
}  // namespace geolens
