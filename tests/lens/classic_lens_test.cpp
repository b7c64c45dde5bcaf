// The classic lenses: their point functions, the ringed mesh they are evaluated on, the identity
// at zoom 1, the known distortion of the Sarkar-Brown fisheye, the zoom-in's inset and hidden
// ring, and matching to a target zoom.

#include "geolens/lens/classic_lens.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geolens/core/errors.h"
#include "geolens/measure/distortion.h"
#include "lens/focus_lens.h"

namespace geolens {
namespace {

constexpr double kPi = std::numbers::pi;

double mean_distance(const Eigen::MatrixX2d& P, const Eigen::MatrixX3i& F, Eigen::Index f,
                     const Eigen::Vector2d& c) {
  double d = 0;
  for (int k = 0; k < 3; ++k) d += (P.row(F(f, k)).transpose() - c).norm() / 3;
  return d;
}

double signed_area(const Eigen::MatrixX2d& P, const Eigen::MatrixX3i& F, Eigen::Index f) {
  const Eigen::Vector2d a = P.row(F(f, 1)) - P.row(F(f, 0)), b = P.row(F(f, 2)) - P.row(F(f, 0));
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

TEST(Baselines, PointFunctionsRunFromCentreToRimAndAreIdentityOutside) {
  for (ClassicLens lens : kClassicLenses) {
    SCOPED_TRACE(to_string(lens));
    for (double zoom : {1.0, 2.0, 3.5, 8.0}) {
      EXPECT_EQ(classic_source_distance(lens, 0, zoom), 0);
      EXPECT_EQ(classic_source_distance(lens, 1, zoom), 1);
      EXPECT_EQ(classic_source_distance(lens, 1.7, zoom), 1.7);
      // Magnification z at the centre: T'(0) = 1 / z.
      EXPECT_NEAR(classic_source_distance(lens, 1e-7, zoom) / 1e-7, 1 / zoom, 1e-5);
      double previous = 0;
      for (int i = 1; i < 1000; ++i) {
        const double u = i / 1000.0, t = classic_source_distance(lens, u, zoom);
        EXPECT_GT(t, previous) << u;
        if (zoom == 1) EXPECT_NEAR(t, u, 1e-15);
        previous = t;
      }
      // Continuous at the rim except the zoom-in's jump from 1 / z to 1.
      const double inside = classic_source_distance(lens, 1 - 1e-9, zoom);
      EXPECT_NEAR(inside, lens == ClassicLens::kZoomIn ? 1 / zoom : 1.0, 1e-6);
    }
  }
  EXPECT_THROW(classic_source_distance(ClassicLens::kFisheye, -0.1, 2), InvalidInput);
  EXPECT_THROW(classic_source_distance(ClassicLens::kFisheye, 0.5, 0.9), InvalidInput);
  EXPECT_THROW(classic_source_distance(ClassicLens::kFisheye, NAN, 2), InvalidInput);
}

TEST(Baselines, SarkarBrownInverseInvertsG) {
  // G(t) = (d + 1) t / (d t + 1) (Sarkar and Brown 1992) applied to T(u) gives u back.
  for (double zoom : {1.5, 2.0, 4.0}) {
    const double d = zoom - 1;
    for (double u = 0.05; u < 1; u += 0.05) {
      const double t = classic_source_distance(ClassicLens::kFisheye, u, zoom);
      EXPECT_NEAR((d + 1) * t / (d * t + 1), u, 1e-12);
    }
  }
}

TEST(Baselines, RingedGridFollowsEveryRingAndCoversTheImage) {
  // One ring well inside, one crossing the top-left corner of the image.
  const std::vector<Ring> rings = {{{200, 150}, 37.5}, {{200, 150}, 75}, {{20, 30}, 60}};
  const PlanarMesh mesh = ringed_grid(400, 300, 120, rings);
  double area = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const double a = signed_area(mesh.V, mesh.F, f);
    EXPECT_GT(a, 1e-3) << f;
    area += a;
    for (const Ring& ring : rings) {
      bool inside = false, outside = false;
      for (int k = 0; k < 3; ++k) {
        const double d = (mesh.V.row(mesh.F(f, k)).transpose() - ring.center).norm() - ring.radius;
        inside = inside || d < -1e-9 * ring.radius;
        outside = outside || d > 1e-9 * ring.radius;
      }
      EXPECT_FALSE(inside && outside) << "triangle " << f << " crosses a ring";
    }
  }
  EXPECT_NEAR(area, 400.0 * 300.0, 1e-6);
  EXPECT_GE(mesh.V.col(0).minCoeff(), 0);
  EXPECT_LE(mesh.V.col(0).maxCoeff(), 400);
  EXPECT_GE(mesh.V.col(1).minCoeff(), 0);
  EXPECT_LE(mesh.V.col(1).maxCoeff(), 300);
  // The sides flags mark exactly the vertices on the image's sides, the ring's crossings of
  // the top and left sides among them.
  ASSERT_EQ(mesh.sides.size(), size_t(mesh.V.rows()));
  int on_sides = 0;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    const double x = mesh.V(i, 0), y = mesh.V(i, 1);
    const uint8_t expected = uint8_t((x == 0 ? kLeft : 0) | (x == 400 ? kRight : 0) |
                                     (y == 0 ? kTop : 0) | (y == 300 ? kBottom : 0));
    EXPECT_EQ(mesh.sides[size_t(i)], expected) << i;
    on_sides += expected != 0;
  }
  const Grid grid = make_grid(400, 300, 120);
  EXPECT_EQ(on_sides, 2 * (grid.columns + grid.rows) - 4 + 2);  // + the ring's two crossings
}

TEST(Baselines, EveryLensAtZoomOneIsTheIdentity) {
  const std::vector<CircleLens> lenses = {{{150, 120}, 80, 1}, {{330, 200}, 50, 1}};
  for (ClassicLens kind : kClassicLenses) {
    SCOPED_TRACE(to_string(kind));
    const WarpMesh warp = classic_warp(kind, lenses, 400, 300, 100);
    const TriangleDistortion m = measure_triangles(warp);
    EXPECT_LT((m.magnification.array() - 1).abs().maxCoeff(), 1e-9);
    EXPECT_LT(m.conformal.maxCoeff(), 1e-9);
    EXPECT_EQ(m.flipped.count(), 0);
    const RegionStatistics r = measure_regions(warp, m, lenses, 400, 300);
    EXPECT_NEAR(r.occluded_area, 0, 1e-6);
  }
}

TEST(Baselines, EveryLensCoversTheScreenOnceWithoutFlipsUpToZoomEight) {
  const std::vector<CircleLens> lenses = {{{150, 120}, 80, 8}, {{330, 200}, 50, 3}};
  for (ClassicLens kind : kClassicLenses) {
    SCOPED_TRACE(to_string(kind));
    const WarpMesh warp = classic_warp(kind, lenses, 400, 300, 150);
    EXPECT_EQ(measure_triangles(warp).flipped.count(), 0);
    double screen_area = 0;
    for (Eigen::Index f = 0; f < warp.F.rows(); ++f)
      screen_area += signed_area(warp.screen, warp.F, f);
    EXPECT_NEAR(screen_area, 400.0 * 300.0, 1e-6);
  }
}

TEST(Baselines, SarkarBrownShapeDistortionIsDTimesDistanceUpToTheRim) {
  // Radial stretch G'(t) = (d + 1) / (d t + 1)^2, tangential G(t) / t = (d + 1) / (d t + 1):
  // s1 / s2 - 1 = d t, so d at the rim.
  for (double zoom : {2.0, 3.0}) {
    const double d = zoom - 1;
    const CircleLens lens{{256, 256}, 150, zoom};
    const WarpMesh warp = classic_warp(ClassicLens::kFisheye, {lens}, 512, 512, 200);
    const TriangleDistortion m = measure_triangles(warp);
    double rim_max = 0;
    for (Eigen::Index f = 0; f < warp.F.rows(); ++f) {
      const double t = mean_distance(warp.source, warp.F, f, lens.center) / lens.radius;
      if (t >= 1) {
        EXPECT_LT(m.conformal(f), 1e-9);
        continue;
      }
      EXPECT_NEAR(m.conformal(f), d * t, 0.05 * d) << "t = " << t;
      if (t > 0.95) rim_max = std::max(rim_max, m.conformal(f));
    }
    EXPECT_NEAR(rim_max, d, 0.02 * d);
  }
}

TEST(Baselines, ZoomInIsUndistortedAndHidesItsRing) {
  for (double zoom : {2.0, 3.0}) {
    const CircleLens lens{{256, 240}, 150, zoom};
    const WarpMesh warp = classic_warp(ClassicLens::kZoomIn, {lens}, 512, 480, 200);
    const TriangleDistortion m = measure_triangles(warp);
    EXPECT_LT(m.conformal.maxCoeff(), 1e-9);
    EXPECT_EQ(m.flipped.count(), 0);
    double inset_area = 0;
    for (Eigen::Index f = 0; f < warp.F.rows(); ++f) {
      const double d = mean_distance(warp.source, warp.F, f, lens.center);
      const bool inset = d < lens.radius / zoom;
      EXPECT_NEAR(m.magnification(f), inset ? zoom : 1.0, 1e-9);
      EXPECT_FALSE(d > lens.radius / zoom && d < lens.radius);  // the hidden ring
      if (inset) inset_area += m.source_area(f);
    }
    const RegionStatistics r = measure_regions(warp, m, {lens}, 512, 480);
    const double ring = kPi * lens.radius * lens.radius * (1 - 1 / (zoom * zoom));
    EXPECT_NEAR(r.occluded_area / ring, 1, 0.002);
    EXPECT_NEAR(inset_area / (kPi * std::pow(lens.radius / zoom, 2)), 1, 0.002);
    // Inside the lens the focus and the transition are both the uniform inset.
    EXPECT_NEAR(r.focus.magnification_min, zoom, 1e-9);
    EXPECT_NEAR(r.transition.magnification_max, zoom, 1e-9);
  }
}

TEST(Baselines, FlatTopsAndBifocalHaveAUniformUndistortedFocus) {
  // Two lenses of different zooms: each focus is uniform on its own.
  const std::vector<CircleLens> lenses = {{{200, 256}, 150, 2.5}, {{500, 256}, 120, 4}};
  for (ClassicLens kind : {ClassicLens::kBifocal, ClassicLens::kFlattopLinear,
                           ClassicLens::kFlattopCosine, ClassicLens::kPowerRing}) {
    SCOPED_TRACE(to_string(kind));
    const WarpMesh warp = classic_warp(kind, lenses, 700, 512, 250);
    const TriangleDistortion m = measure_triangles(warp);
    const RegionStatistics r = measure_regions(warp, m, lenses, 700, 512);
    EXPECT_GT(r.focus.triangles, 100);
    EXPECT_NEAR(r.focus.magnification_min, 2.5, 1e-9);
    EXPECT_NEAR(r.focus.magnification_max, 4, 1e-9);
    EXPECT_NEAR(r.focus_uniformity, 1, 1e-9);
    EXPECT_LT(r.focus.conformal_max, 1e-9);
    EXPECT_GT(r.transition.conformal_max, 0.5);
    EXPECT_LT(r.context.conformal_max, 1e-9);
  }
}

TEST(Baselines, FlatTopLinearHasItsAnalyticRimDistortion) {
  // At the rim the gain M = 1 with slope M' = -(z - 1) / (1 - a): radial stretch 1 / (1 - M'),
  // tangential 1, so s1 / s2 - 1 = -M' = (z - 1) / (1 - a).
  const double zoom = 2, a = kFocusFraction;
  const CircleLens lens{{256, 256}, 150, zoom};
  const WarpMesh warp = classic_warp(ClassicLens::kFlattopLinear, {lens}, 512, 512, 200);
  const RegionStatistics r = measure_regions(warp, measure_triangles(warp), {lens}, 512, 512);
  EXPECT_NEAR(r.transition.conformal_max, (zoom - 1) / (1 - a), 0.03 * (zoom - 1) / (1 - a));
}

// The power ring reaches the radial bound: its shape distortion is 1 / k - 1 everywhere in the
// ring, the least any radial lens with a uniform focus of source radius a r / z and the identity
// beyond r can have (R / r_f = z / a), on a 1 px mesh (2 px cells add 2 - 3 % at the focus rim).
TEST(Baselines, PowerRingReachesTheRadialBound) {
  for (const double zoom : {2.0, 3.0}) {
    SCOPED_TRACE(zoom);
    const CircleLens lens{{300, 300}, 250, zoom};
    const WarpMesh warp = classic_warp(ClassicLens::kPowerRing, {lens}, 600, 600, 600);
    const RegionStatistics r = measure_regions(warp, measure_triangles(warp), {lens}, 600, 600);
    const double bound = radial_distortion_bound(zoom, zoom / kFocusFraction);
    EXPECT_NEAR(r.transition.conformal_max / bound, 1.0, 0.02);
    EXPECT_LT(r.focus.conformal_max, 1e-9);
    // The flat tops of the same proportions distort more.
    for (ClassicLens other : {ClassicLens::kFlattopLinear, ClassicLens::kFlattopCosine}) {
      const WarpMesh w = classic_warp(other, {lens}, 600, 600, 300);
      EXPECT_GT(measure_regions(w, measure_triangles(w), {lens}, 600, 600).transition.conformal_max,
                1.5 * bound);
    }
  }
}

TEST(Baselines, MatchingReachesTheTargetZoomWithTheSameMeasure) {
  const std::vector<CircleLens> targets = {{{200, 200}, 120, 2.2}, {{420, 150}, 60, 1.5}};
  const std::vector<double> radius = {9, 5};
  for (ClassicLens kind : kClassicLenses) {
    SCOPED_TRACE(to_string(kind));
    const Magnification m = match_classic_lens(kind, targets, radius, 500, 400, 150);
    const TriangleDistortion measures = measure_triangles(m.warp);
    for (size_t k = 0; k < targets.size(); ++k) {
      EXPECT_NEAR(m.zoom_measured[k] / targets[k].zoom, 1, 0.005);
      EXPECT_DOUBLE_EQ(magnification_at(m.warp, measures, targets[k].center, radius[k]),
                       m.zoom_measured[k]);
      if (kind == ClassicLens::kFisheye || kind == ClassicLens::kFisheyeSmooth)
        EXPECT_GT(m.zoom_parameter[k], targets[k].zoom);  // peaked: the disk mean is lower
      else
        EXPECT_NEAR(m.zoom_parameter[k], targets[k].zoom, 1e-9);  // uniform around the centre
    }
  }
}

TEST(Baselines, RejectsBadLenses) {
  const auto warp = [](std::vector<CircleLens> lenses, int mesh = 50) {
    return classic_warp(ClassicLens::kFisheye, lenses, 400, 300, mesh);
  };
  EXPECT_THROW(warp({}), InvalidInput);
  EXPECT_THROW(warp({{{100, 100}, 0, 2}}), InvalidInput);
  EXPECT_THROW(warp({{{100, 100}, 50, 0.5}}), InvalidInput);
  EXPECT_THROW(warp({{{500, 100}, 50, 2}}), InvalidInput);
  EXPECT_THROW(warp({{{100, 100}, 50, 2}, {{180, 100}, 50, 2}}), InvalidInput);  // overlap
  EXPECT_THROW(warp({{{100, 100}, 50, 2}}, 3), InvalidInput);
  EXPECT_THROW(match_classic_lens(ClassicLens::kBifocal, {{{100, 100}, 50, 2}}, {}, 400, 300),
               InvalidInput);
  EXPECT_THROW(ringed_grid(400, 300, 50, {{{100, 100}, -1}}), InvalidInput);
  EXPECT_EQ(to_string(ClassicLens::kFlattopCosine), "flattop_cosine");
  EXPECT_EQ(to_string(ClassicLens::kPowerRing), "power_ring");
}

}  // namespace
}  // namespace geolens
