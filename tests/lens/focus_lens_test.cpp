// The focus lens: the region given is magnified as a whole, uniformly and without rotation, the
// context gives way within the footprint, and nothing beyond it moves.

#include "lens/focus_lens.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <random>
#include <string>

#include "core/thread_pool.h"
#include "geolens/core/errors.h"
#include "geolens/eval/comparison.h"
#include "geolens/geometry/grid.h"
#include "geolens/io/image.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_options.h"
#include "geolens/lens/lens_session.h"
#include "geolens/measure/distortion.h"
#include "geolens/warp/warp_map.h"
#include "geometry/conforming_mesh.h"
#include "lens/texture_map.h"

namespace geolens {
namespace {

using Points = std::vector<Eigen::Vector2d>;

Points translated(Points p, const Eigen::Vector2d& by) {
  for (Eigen::Vector2d& v : p) v += by;
  return p;
}

// Shapes around the origin: an L of 60 px arms in a 200 px box, a five-pointed star of outer
// radius 120 px, a 400 x 40 px strip (10:1).
const Points kL = {{-100, -100}, {-40, -100}, {-40, 40}, {100, 40}, {100, 100}, {-100, 100}};
const Points kStrip = {{-200, -20}, {200, -20}, {200, 20}, {-200, 20}};
Points star() {
  Points p;
  for (int k = 0; k < 10; ++k) {
    const double r = k % 2 == 0 ? 120 : 0.382 * 120,
                 a = std::numbers::pi / 2 + k * std::numbers::pi / 5;
    p.emplace_back(r * std::cos(a), -r * std::sin(a));
  }
  return p;
}

// An outline traced by many nearly straight corners (as a mask's or a drawn shape's is): a 120-gon
// ellipse of 60 x 40 px with a bite of radius 15 px out of its lower right.
Points bitten_ellipse() {
  Points p;
  const Eigen::Vector2d bite(54, 24);
  for (int k = 0; k < 120; ++k) {
    const double a = 2 * std::numbers::pi * k / 120;
    Eigen::Vector2d q(60 * std::cos(a), 40 * std::sin(a));
    if ((q - bite).norm() < 15) q = bite + (q - bite).normalized() * 15;
    if (p.empty() || (q - p.back()).norm() >= 0.5) p.push_back(q);
  }
  return p;
}

TEST(FocusLens, RadialBoundIsThePowerLawsDistortion) {
  EXPECT_NEAR(radial_distortion_bound(2, 4), 1.0, 1e-12);  // k = 1 / 2
  EXPECT_NEAR(radial_distortion_bound(3, 9), 1.0, 1e-12);
  EXPECT_NEAR(radial_distortion_bound(2, 8), 0.5, 1e-12);  // k = 2 / 3
  EXPECT_EQ(radial_distortion_bound(1, 2), 0.0);
  EXPECT_TRUE(std::isinf(radial_distortion_bound(4, 4)));
  EXPECT_THROW(radial_distortion_bound(2, 1), InvalidInput);
  // The rim's: 1.15 times the power law's where the ring has room (a <= 0.7), the power law's
  // where it has least (a >= 0.85), and between the two in between.
  EXPECT_NEAR(rim_distortion_bound(2, 4), 1.15 * radial_distortion_bound(2, 4), 1e-12);
  EXPECT_NEAR(rim_distortion_bound(2, 8), 1.15 * radial_distortion_bound(2, 8), 1e-12);
  EXPECT_NEAR(rim_distortion_bound(std::pow(10, 0.8), 10),
              1.05 * radial_distortion_bound(std::pow(10, 0.8), 10), 1e-12);
  EXPECT_NEAR(rim_distortion_bound(std::pow(10, 0.9), 10),
              radial_distortion_bound(std::pow(10, 0.9), 10), 1e-12);
  for (double a = 0.05; a < 1; a += 0.05) {
    const double zoom = std::pow(10, a);
    EXPECT_GE(rim_distortion_bound(zoom, 10), radial_distortion_bound(zoom, 10)) << a;
    EXPECT_LE(rim_distortion_bound(zoom, 10), 1.15 * radial_distortion_bound(zoom, 10) + 1e-12)
        << a;
  }
  EXPECT_TRUE(std::isinf(rim_distortion_bound(4, 4)));
}

TEST(FocusLens, RegionsMeasureDistanceAndReach) {
  const Region c = Region::circle({100, 100}, 50);
  EXPECT_DOUBLE_EQ(c.distance({180, 100}), 30);
  EXPECT_EQ(c.distance({110, 90}), 0);
  EXPECT_DOUBLE_EQ(c.reach(), 50);
  const Region square = Region::polygon({{100, 100}, {200, 100}, {200, 200}, {100, 200}});
  EXPECT_NEAR(square.distance({250, 150}), 50, 1e-9);
  EXPECT_NEAR(square.distance({230, 240}), 50, 1e-9);
  EXPECT_EQ(square.distance({150, 150}), 0);
  EXPECT_NEAR(square.reach(), (square.peak() - Eigen::Vector2d(100, 100)).norm(), 1.5);
  Image mask(64, 64, 1);
  for (int y = 10; y < 30; ++y)
    for (int x = 20; x < 40; ++x) mask.at(x, y)[0] = 255;
  const Region m = Region::from_mask(mask).front();
  EXPECT_EQ(m.distance({25.5, 15.5}), 0);
  // The blob's smooth outline (Region::from_mask): on the pixels' edges along a side, its corners
  // rounded by less than a pixel.
  EXPECT_NEAR(m.distance({50, 20}), 10, 1e-9);  // the blob's pixels end at x = 40
  EXPECT_NEAR(m.distance({43, 34}), 5, 1.0);    // 3-4-5 from the corner (40, 30)
  EXPECT_GT(m.reach(), 10 * std::numbers::sqrt2 - 1);
}

// A mesh fine enough that the focus is held within a few percent of its reach in an image three
// times the footprint's size.
LensOptions fine() {
  LensOptions options;
  options.mesh = 250;
  return options;
}

// A lens of `shape` centred in an image big enough for its footprint at `zoom`, solved with the
// defaults: the focus model.
struct Solved {
  Lens lens;
  LensResult result;
  FocusMeasure focus;
  DistortionSummary summary;
};
Solved solve_centred(const Points& shape, double zoom, double radius = 0) {
  const Region probe = radius > 0 ? Region::circle({0, 0}, radius) : Region::polygon(shape);
  // The footprint (2 zoom reach) and room beyond it, so the image border does not limit the zoom.
  const double side = std::ceil(3 * (2 * zoom * probe.reach()) + 200);
  const Eigen::Vector2d centre(side / 2, side / 2);
  Lens lens{radius > 0 ? Region::circle(centre, radius)
                       : Region::polygon(translated(shape, centre - probe.peak())),
            zoom};
  const GeometricLens geometric(side, side, fine());
  Solved s{lens, geometric.solve({lens}), {}, {}};
  const TriangleDistortion measures = measure_triangles(s.result.warp);
  s.focus = measure_foci(s.result.warp, measures, {lens}).front();
  s.summary = summarize(measures);
  return s;
}

void expect_uniform_focus(const Solved& s, double zoom) {
  EXPECT_EQ(s.result.model, LensModel::kFocus);
  ASSERT_EQ(s.result.zoom_fits.size(), 1u);
  EXPECT_GE(s.result.zoom_fits[0], zoom);
  EXPECT_NEAR(s.focus.zoom / zoom, 1.0, 0.05);
  EXPECT_LE(s.focus.uniformity, 1.1);
  EXPECT_LE(s.focus.shape_max, 0.1);
  EXPECT_LE(s.focus.shape_mean, s.focus.shape_max);
  EXPECT_EQ(s.summary.flipped, 0);
  EXPECT_EQ(s.focus.displacement_beyond_footprint, 0.0);
  EXPECT_GT(s.focus.footprint_radius, s.lens.region.reach());
}

class FocusZoom : public ::testing::TestWithParam<double> {};

TEST_P(FocusZoom, CircleIsMagnifiedUniformlyAndNothingBeyondItsFootprintMoves) {
  expect_uniform_focus(solve_centred({}, GetParam(), 150), GetParam());
}
TEST_P(FocusZoom, LIsMagnifiedAsAWhole) {
  expect_uniform_focus(solve_centred(kL, GetParam()), GetParam());
}
TEST_P(FocusZoom, StarIsMagnifiedAsAWhole) {
  expect_uniform_focus(solve_centred(star(), GetParam()), GetParam());
}
TEST_P(FocusZoom, TenToOneStripIsMagnifiedAlongAsMuchAsAcross) {
  expect_uniform_focus(solve_centred(kStrip, GetParam()), GetParam());
}

INSTANTIATE_TEST_SUITE_P(Zooms, FocusZoom, ::testing::Values(2.0, 3.0, 4.0));

// Its mesh fans each corner out by halving the angle there: splitting the far edge at its midpoint
// crept towards a nearly straight corner in slivers (down to 1e-4 px) that folded under the ring,
// and this outline fitted zoom 1.0 of 3 on a 1024 px image at mesh 100; now 1.93 (still short of
// 3: the ring shears the mesh where the bite's horns meet the ellipse).
TEST(FocusLens, OutlineOfManyNearlyStraightCornersFitsMostOfZoomThree) {
  LensOptions options;
  options.mesh = 100;
  const Lens lens{Region::polygon(translated(bitten_ellipse(), {512, 512})), 3};
  const LensResult r = GeometricLens(1024, 1024, options).solve({lens});
  ASSERT_EQ(r.zoom_fits.size(), 1u);
  EXPECT_GT(r.zoom_fits[0], 1.9);
  const TriangleDistortion measures = measure_triangles(r.warp);
  EXPECT_EQ(summarize(measures).flipped, 0);
  const FocusMeasure focus = measure_foci(r.warp, measures, {lens}).front();
  EXPECT_NEAR(focus.zoom / r.zoom_fits[0], 1.0, 0.05);
  EXPECT_LE(focus.uniformity, 1.1);
}

// A mask's blob (a disk with a notch) the same way.
TEST(FocusLens, MaskBlobIsMagnifiedAsAWhole) {
  for (const double zoom : {2.0, 3.0, 4.0}) {
    const int side = int(3 * 2 * zoom * 120 + 200);  // the reach from the peak is below 120
    Image mask(side, side, 1);
    const double c = side / 2.0;
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x)
        if (std::hypot(x + 0.5 - c, y + 0.5 - c) < 80 && !(x > c && std::abs(y + 0.5 - c) < 15))
          mask.at(x, y)[0] = 255;
    const Lens lens{Region::from_mask(mask).front(), zoom};
    const LensResult r = GeometricLens(side, side, fine()).solve({lens});
    const TriangleDistortion measures = measure_triangles(r.warp);
    const Solved s{lens, r, measure_foci(r.warp, measures, {lens}).front(), summarize(measures)};
    SCOPED_TRACE(zoom);
    expect_uniform_focus(s, zoom);
  }
}

// Near a border the ring is shorter on that side: a lens asks for no more than fits there, and a
// region over the image's corner is magnified about the corner, which stays.
TEST(FocusLens, ALensAtTheCornerKeepsTheCornerAndFitsItsZoom) {
  const Lens lens{Region::circle({0, 0}, 100), 2.0};
  const GeometricLens geometric(1024, 1024);
  const LensResult r = geometric.solve({lens});
  ASSERT_EQ(r.zoom_fits.size(), 1u);
  EXPECT_GE(r.zoom_fits[0], 2.0);
  const FocusMeasure f = measure_foci(r.warp, measure_triangles(r.warp), {lens}).front();
  EXPECT_NEAR(f.zoom, 2.0, 0.1);
  EXPECT_LE(f.uniformity, 1.1);
  EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0);
  // The output still fills the frame: the image's corners stay where they are.
  EXPECT_EQ(r.warp.screen.colwise().minCoeff(), Eigen::RowVector2d(0, 0));
  EXPECT_EQ(r.warp.screen.colwise().maxCoeff(), Eigen::RowVector2d(1024, 1024));
}

TEST(FocusLens, ALensThatDoesNotFitIsSolvedAtTheZoomThatFits) {
  const Lens lens{Region::circle({300, 300}, 200), 3.0};
  const LensResult r = GeometricLens(1024, 1024).solve({lens});
  ASSERT_EQ(r.zoom_fits.size(), 1u);
  EXPECT_LT(r.zoom_fits[0], 3.0);
  EXPECT_NEAR(r.zoom_measured[0], std::max(1.0, r.zoom_fits[0]), 0.05 * r.zoom_fits[0]);
  EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0);
}

// The zoom got, as a function of the zoom asked, is the one asked where that fits and never
// falls as the request grows: a lens's footprint follows the zoom it gets (a footprint scaled
// with the request hit the image sides sooner: a phrase near a page's side got 1.97 at zoom 2
// and 1.65 at zoom 4). Zoom 1 to 8 in steps of 0.25, for a circle, a polygon and a mask near a
// side of the image, each measured over its region.
TEST(FocusLens, ZoomGotIsTheZoomAskedWhereItFitsAndNeverFallsAsTheRequestGrows) {
  Image mask(1024, 1024, 1);
  for (int y = 400; y < 470; ++y)
    for (int x = 40; x < 160; ++x) mask.at(x, y)[0] = 255;
  const std::vector<std::pair<std::string, Region>> regions = {
      {"circle", Region::circle({120, 512}, 60)},
      {"phrase", Region::polygon({{85, 400}, {420, 400}, {420, 429}, {85, 429}})},
      {"mask", Region::from_mask(mask).front()}};
  LensOptions options;
  options.mesh = 60;
  const GeometricLens geometric(1024, 1024, options);
  for (const auto& [name, region] : regions) {
    SCOPED_TRACE(name);
    double last = 1;
    for (double zoom = 1; zoom <= 8; zoom += 0.25) {
      SCOPED_TRACE(zoom);
      const Lens lens{region, zoom};
      const LensResult r = geometric.solve({lens});
      const double got = r.zoom_fits.at(0);
      EXPECT_LE(got, zoom);
      EXPECT_GE(got, last * (1 - 1e-6));
      EXPECT_EQ(r.zoom_fit_reasons.at(0).empty(), got >= zoom * (1 - 1e-3));
      const FocusMeasure focus = measure_foci(r.warp, measure_triangles(r.warp), {lens}).front();
      EXPECT_NEAR(focus.zoom / got, 1, 0.01);
      last = got;
    }
    EXPECT_GT(last, 1.3);  // each gets a real zoom near its side
  }
}

// A lens that fits gets its zoom exactly and no warning's reason (zoom 5 on a 4725 px map was
// told it did not fit: "the largest zoom that fits is 5", 4.999999999999999; the same at 7).
TEST(FocusLens, ALensThatFitsGetsExactlyItsZoomAndNoReason) {
  for (double zoom = 2; zoom <= 8; zoom += 1) {
    const LensResult r =
        GeometricLens(4725, 4050).solve({Lens{Region::circle({2362, 2025}, 120), zoom}});
    EXPECT_EQ(r.zoom_fits.at(0), zoom);
    EXPECT_EQ(r.zoom_fit_reasons.at(0), "");
  }
}

// A lens that gets less than it asks is told what limits it: the side it is near (and how near),
// the lens beside it, or its footprint's ratio.
TEST(FocusLens, ALensShortOfItsZoomIsToldWhatLimitsIt) {
  const GeometricLens geometric(1024, 1024);
  const LensResult side = geometric.solve({Lens{Region::circle({140, 512}, 100), 4}});
  EXPECT_LT(side.zoom_fits.at(0), 4);
  EXPECT_EQ(side.zoom_fit_reasons.at(0).rfind("the image's left side, 40 px from the region", 0),
            0u)
      << side.zoom_fit_reasons[0];
  // Two lenses whose rings at 6 would not fit side by side, and which would fit less as one.
  const LensResult pair = GeometricLens(2048, 2048)
                              .solve({Lens{Region::circle({824, 1024}, 40), 6},
                                      Lens{Region::circle({1224, 1024}, 40), 6}});
  for (size_t k : {0, 1}) EXPECT_LT(pair.zoom_fits.at(k), 6);
  EXPECT_EQ(pair.zoom_fit_reasons.at(0).rfind("lens 2 beside it", 0), 0u)
      << pair.zoom_fit_reasons[0];
  EXPECT_EQ(pair.zoom_fit_reasons.at(1).rfind("lens 1 beside it", 0), 0u)
      << pair.zoom_fit_reasons[1];
  Lens tight{Region::circle({512, 512}, 50), 2.9};
  tight.footprint = 3;
  const LensResult ratio = geometric.solve({tight});
  EXPECT_LT(ratio.zoom_fits.at(0), 2.9);
  EXPECT_EQ(ratio.zoom_fit_reasons.at(0).rfind("its footprint", 0), 0u)
      << ratio.zoom_fit_reasons[0];
}

// A lens held back by the room its neighbour leaves it is told so wherever the two stay apart,
// though the fit then lowers it by a rounding (a lens r 150 asked 4 beside one asked 2, 900 px
// away on a relief map, was told "the image's right side, 2205 px from the region", the side the
// two would have as one). Moved apart in 25 px steps: the neighbour keeps its 2, the lens gets
// more at each step.
TEST(FocusLens, ALensHeldByItsNeighboursRoomIsToldSoAllTheWay) {
  const GeometricLens geometric(4725, 4050);
  double last = 0;
  for (double gap = 900; gap <= 1100; gap += 25) {
    const LensResult r = geometric.solve({Lens{Region::circle({1500, 2000}, 150), 4},
                                          Lens{Region::circle({1500 + gap, 2000}, 120), 2}});
    EXPECT_EQ(r.zoom_fits.at(1), 2) << gap;
    EXPECT_TRUE(r.zoom_fit_reasons.at(1).empty()) << gap << ": " << r.zoom_fit_reasons[1];
    EXPECT_LT(r.zoom_fits.at(0), 4) << gap;
    EXPECT_GT(r.zoom_fits.at(0), last) << gap;
    last = r.zoom_fits[0];
    EXPECT_EQ(r.zoom_fit_reasons.at(0), "lens 2 beside it (lenses farther apart fit more)") << gap;
  }
}

// Lenses magnified as one (their magnified foci overlap) are solved at their group's zoom, the
// larger asked, lowered where the group does not fit: each is told the zoom it gets, and only the
// one that gets less than asked is warned, with what limits the group and with which lens (the
// lens asked 3 was told "2.60 of the 3 asked, limited by the image's left side" where it was shown
// at 3.34). Moved towards each other in 100 px steps, the report and the picture agree at each;
// the group gets lens 1's 4 from 200 px apart.
TEST(FocusLens, LensesMagnifiedAsOneAreToldTheZoomTheyGet) {
  const GeometricLens geometric(4725, 4050);
  int short_of_4 = 0;
  for (const double gap : {400.0, 300.0, 200.0, 100.0, 0.0}) {
    const std::vector<Lens> lenses = {Lens{Region::circle({1500, 2000}, 150), 4},
                                      Lens{Region::circle({1770 + gap, 2000}, 120), 3}};
    const LensResult r = geometric.solve(lenses);
    const std::vector<FocusMeasure> f = measure_foci(r.warp, measure_triangles(r.warp), lenses);
    for (size_t k : {0, 1}) EXPECT_NEAR(r.zoom_fits[k] / f[k].zoom, 1, 0.01) << gap << " " << k;
    EXPECT_NEAR(r.zoom_fits[0], r.zoom_fits[1], 1e-12) << gap;
    EXPECT_GT(r.zoom_fits[1], 3) << gap;  // the group at more than lens 2 asked: no reason
    EXPECT_TRUE(r.zoom_fit_reasons[1].empty()) << gap << ": " << r.zoom_fit_reasons[1];
    if (r.zoom_fits[0] < 4 * (1 - 1e-3)) {  // the group does not fit lens 1's 4
      ++short_of_4;
      EXPECT_NE(r.zoom_fit_reasons[0].find("; magnified as one with lens 2"), std::string::npos)
          << gap << ": " << r.zoom_fit_reasons[0];
    } else {
      EXPECT_TRUE(r.zoom_fit_reasons[0].empty()) << gap << ": " << r.zoom_fit_reasons[0];
    }
  }
  EXPECT_GE(short_of_4, 2);  // 400 and 300 px apart: 3.62 and 3.96
}

// A circle dragged in 1 px steps towards the top side and across it gets the zoom it asks at
// every step: where its ring about the centre has too little room the magnified focus slides
// away from the side (it got 1.02 at 1 px from the side before it slid, 3 touching it), and
// once it touches the side it is magnified about a point on it. Nothing flips on the way.
TEST(FocusLens, DraggedToAndAcrossASideItGetsItsZoomAllTheWay) {
  const GeometricLens geometric(2048, 1350);
  for (int y = 300; y >= 0; --y) {
    SCOPED_TRACE(y);
    const Lens lens{Region::circle({1265, double(y)}, 50), 3};
    const LensResult r = geometric.solve({lens});
    EXPECT_NEAR(r.zoom_fits.at(0), 3, 3e-9);
    EXPECT_EQ(r.zoom_fit_reasons.at(0), "");
    const TriangleDistortion measures = measure_triangles(r.warp);
    EXPECT_EQ(summarize(measures).flipped, 0);
    EXPECT_NEAR(measure_foci(r.warp, measures, {lens}).front().zoom, 3, 3e-4);
  }
}

// A circle pushed across a side near another (254 px below the top, the ring about the side's
// point short of room along the side) slides along the side, so the side's points stay on it:
// in 1 px steps from touching the side to 60 px across it its zoom changes by at most 0.03 a
// pixel and grows as less of it is left (magnified about the side's point alone, it got 1.95
// touching and 2.51 at 60 px; now 2.67 and 3.45).
TEST(FocusLens, PushedAcrossASideItSlidesAlongIt) {
  const GeometricLens geometric(1024, 768);
  double last = 0;
  for (int depth = 0; depth <= 60; ++depth) {
    SCOPED_TRACE(depth);
    const Lens lens{Region::circle({79.0 - depth, 254}, 79), 3.69};
    const LensResult r = geometric.solve({lens});
    const double got = r.zoom_fits.at(0);
    if (depth > 0) {
      EXPECT_LE(std::abs(got - last), 0.03);
      EXPECT_GE(got, last - 1e-9);
    }
    last = got;
    const TriangleDistortion measures = measure_triangles(r.warp);
    EXPECT_EQ(summarize(measures).flipped, 0);
    EXPECT_NEAR(measure_foci(r.warp, measures, {lens}).front().zoom, got, 3e-4);
    const WarpMap map(r.warp);
    for (double y = 0; y <= 768; y += 16) {
      const std::optional<Eigen::Vector2d> q = map.forward({0, y});
      ASSERT_TRUE(q.has_value());
      EXPECT_NEAR(q->x(), 0, 1e-9) << y;
    }
    if (depth == 0) EXPECT_GT(got, 2.6);
  }
  EXPECT_GT(last, 3.4);
}

// A circle nearing a side in half- and, from 3 px, quarter-pixel steps, to touching it and across:
// its zoom changes by at most 0.02 a step, never for the mesh, and is what its focus measures.
// Within a tenth of its radius of the side it is magnified about the side's point, as it is
// touching it (its slide off the side stretched the gap until the mesh folded: r 22 at 4.26
// got 1.79 and 1.0 at 1 and 0.5 px from the side, and 3.19 at 7-9 px, r 105 at 2.94 got 2.35 a
// quarter pixel off and 2.16 touching); beyond, its slide off the side is held within
// e^(gap / r - 0.1) times that ring's fit.
TEST(FocusLens, NearingASideInQuarterPixelsItsZoomIsContinuous) {
  LensOptions options;
  options.mesh = 100;
  const GeometricLens geometric(1024, 768, options);
  for (const auto& [radius, zoom] : {std::pair{22.0, 4.26}, std::pair{105.0, 2.94}}) {
    double last = 0;
    for (double gap = 14; gap >= -1; gap -= gap > 3 ? 0.5 : 0.25) {
      SCOPED_TRACE("r " + std::to_string(radius) + ", " + std::to_string(gap) + " px off the side");
      const Lens lens{Region::circle({radius + gap, 393.73}, radius), zoom};
      const LensResult r = geometric.solve({lens});
      const double got = r.zoom_fits.at(0);
      EXPECT_FALSE(r.mesh_limited);
      if (gap < 14) EXPECT_LE(std::abs(got - last), 0.02);
      const TriangleDistortion measures = measure_triangles(r.warp);
      EXPECT_EQ(summarize(measures).flipped, 0);
      EXPECT_NEAR(measure_foci(r.warp, measures, {lens}).front().zoom, got, 3e-4);
      last = got;
    }
  }
}

// A circle (r 45 at zoom 3.5 on 1024 x 768, 553 px down) nearing the left side in 1 px steps from
// 50 to 28 px off it, where its slide off the side gives way to the ring about the side's point:
// the two rings are blended (FocusGroup::blend), so the centre of the magnified focus moves by at
// most 25 px a pixel (one ring gave way to the other at once: 113 px between 32 and 31 px off
// the side), the zoom by at most 0.03, and the focus is magnified exactly, nothing flipped.
TEST(FocusLens, NearingASideItsMagnifiedFocusMovesContinuously) {
  LensOptions options;
  options.mesh = 100;
  const GeometricLens geometric(1024, 768, options);
  const double radius = 45;
  double last = 0;
  Eigen::Vector2d shown = Eigen::Vector2d::Zero();
  for (int gap = 50; gap >= 28; --gap) {
    SCOPED_TRACE(std::to_string(gap) + " px off the side");
    const Eigen::Vector2d centre(radius + gap, 553);
    const Lens lens{Region::circle(centre, radius), 3.5};
    const LensResult r = geometric.solve({lens});
    const double got = r.zoom_fits.at(0);
    const std::optional<Eigen::Vector2d> now = WarpMap(r.warp).forward(centre);
    ASSERT_TRUE(now.has_value());
    if (gap < 50) {
      EXPECT_LE((*now - shown).norm(), 25);
      EXPECT_LE(std::abs(got - last), 0.03);
    }
    const TriangleDistortion measures = measure_triangles(r.warp);
    EXPECT_EQ(summarize(measures).flipped, 0);
    EXPECT_NEAR(measure_foci(r.warp, measures, {lens}).front().zoom, got, 3e-4);
    last = got;
    shown = *now;
  }
}

// A circle 20 px below the top side, 160 px from the left one, magnified about the side's point
// above it: its mesh's refinement split three edges at one point, whose merge was refused (each
// step left a triangle flat with the third), and the solve refused the mesh as degenerate. Now
// solved at its zoom, nothing flipped, the focus exact.
TEST(FocusLens, ACircleNearASideHasNoCoincidentVertices) {
  LensOptions options;
  options.mesh = 100;
  const Lens lens{Region::circle({160, 70}, 50), 3};
  LensResult r;
  ASSERT_NO_THROW(r = GeometricLens(1024, 768, options).solve({lens}));
  EXPECT_DOUBLE_EQ(r.zoom_fits.at(0), 3);
  const TriangleDistortion measures = measure_triangles(r.warp);
  EXPECT_EQ(summarize(measures).flipped, 0);
  EXPECT_NEAR(measure_foci(r.warp, measures, {lens}).front().zoom, 3, 3e-4);
}

// A circle dragged in 1 px steps along a side, 6 and 15 px from it, from near one corner to near
// the other (as in geolens-view's drag test, on its 320 x 240 picture): its zoom changes by at
// most 0.03 a pixel, is its own where the corners leave it the room, and is never held back by
// the mesh. (The rim's budget faded linearly with the slide there, a crease along the ray where
// the fade began, and tiny triangles the refinement made along it folded: 11 places 6 px from
// the side got 2.41 for "the mesh" between places that got 3; the repair of the start's folds
// by the neighbours' mean alone left one 15 px from it, x = 183.)
TEST(FocusLens, DraggedAlongASideItsZoomIsContinuous) {
  const GeometricLens geometric(320, 240);
  for (const double gap : {6.0, 15.0}) {
    double last = 0;
    int full = 0;
    for (int x = 60; x <= 260; ++x) {
      SCOPED_TRACE(std::to_string(gap) + " px from the side, x = " + std::to_string(x));
      const Lens lens{Region::circle({double(x), 24 + gap}, 24), 3};
      const LensResult r = geometric.solve({lens});
      const double got = r.zoom_fits.at(0);
      EXPECT_FALSE(r.mesh_limited);
      if (x > 60) EXPECT_LE(std::abs(got - last), 0.03);
      EXPECT_NEAR(measure_foci(r.warp, measure_triangles(r.warp), {lens}).front().zoom, got, 3e-4);
      full += got == 3;
      last = got;
    }
    EXPECT_GE(full, gap == 6 ? 90 : 115);  // 3 from x = 113 to 207 at 6 px, 100 to 220 at 15
  }
}

// A circle (r 50 at zoom 3 on 1024 x 768) dragged 2 px a step along the top side, 20 px below
// it, into the top-left corner, and along the corner's diagonal to touching both sides: its zoom
// changes by at most 0.125 a pixel, never falls below 2.3, is never held back by the mesh, and is
// what its focus measures, nothing flipped. Near the second side it is magnified about their
// corner, held so the zoom is continuous (the ring about the top side's point, sliding along it
// past the corner, folded the mesh: 1.18-1.21 between places that got 2.0-2.6, and 1.0 in the
// last pixels; along the diagonal 1.32 a quarter pixel off both sides, 3 touching them; the
// corner's ring held to 8^(w - 1) times its own fit left 1.95 along the side and 2.09 on the
// diagonal, and changes of 0.13 a pixel).
TEST(FocusLens, DraggedIntoACornerItsZoomIsContinuous) {
  LensOptions options;
  options.mesh = 100;
  const GeometricLens geometric(1024, 768, options);
  const double radius = 50;
  std::vector<Eigen::Vector2d> along, diagonal;
  for (double x = 250; x >= radius; x -= 2) along.emplace_back(x, radius + 20);
  for (double d = 100; d >= 0; d -= 2) diagonal.emplace_back(radius + d, radius + d);
  for (const std::vector<Eigen::Vector2d>* path : {&along, &diagonal}) {
    double last = 0;
    for (const Eigen::Vector2d& centre : *path) {
      SCOPED_TRACE("centre " + std::to_string(centre.x()) + ", " + std::to_string(centre.y()));
      const Lens lens{Region::circle(centre, radius), 3};
      const LensResult r = geometric.solve({lens});
      const double got = r.zoom_fits.at(0);
      EXPECT_FALSE(r.mesh_limited);
      EXPECT_GE(got, 2.3);
      if (&centre != &path->front()) EXPECT_LE(std::abs(got - last), 0.25);
      const TriangleDistortion measures = measure_triangles(r.warp);
      EXPECT_EQ(summarize(measures).flipped, 0);
      EXPECT_NEAR(measure_foci(r.warp, measures, {lens}).front().zoom, got, 3e-4);
      last = got;
    }
    EXPECT_NEAR(last, 3, 1e-9);  // touching the side(s), magnified about the corner at its zoom
  }
}

// A circle (r 50 at zoom 3 on 1024 x 768) dragged 1 px a step along the right side, 20 px from
// it, is magnified about the side's point and gets its zoom at every step. Where a vertex of the
// mesh lay on that point (every 16 px) the point's ray pointed out of the image, so the vertex
// stayed while its neighbours moved with the focus, and the mesh folded: 1.0 at y = 144, 160,
// 176, 192 and 208.
TEST(FocusLens, AboutAPointOfTheRightSideItsCentreMovesWithTheFocus) {
  LensOptions options;
  options.mesh = 100;
  const GeometricLens geometric(1024, 768, options);
  for (int y = 150; y <= 210; ++y) {
    SCOPED_TRACE(y);
    const LensResult r = geometric.solve({Lens{Region::circle({954, double(y)}, 50), 3}});
    EXPECT_DOUBLE_EQ(r.zoom_fits.at(0), 3);
    EXPECT_FALSE(r.mesh_limited);
  }
}

// A hexagon (reach 50 at zoom 3 on 1024 x 768) dragged 2 px a step towards the left side until
// it touches it, and along the top side into the corner: near the side it is magnified about the
// side's point, as a polygon over it is, chosen and held as a circle is (magnify_near_side), so its
// zoom changes by at most 0.3 a step and never falls below 1.5, nothing flips, and it gets 3
// touching the side. (Magnified about its centre, its ring clipped by the side, it fell to 1.0 in
// the last pixels and sprang to 3 when it touched the side.)
TEST(FocusLens, APolygonNearingASideKeepsAContinuousZoom) {
  LensOptions options;
  options.mesh = 100;
  const GeometricLens geometric(1024, 768, options);
  // The hexagon about (x, y), its vertices on the image (a rounding above the top side is 0).
  auto hexagon = [](double x, double y) {
    std::vector<Eigen::Vector2d> vertices;
    for (int k = 0; k < 6; ++k)
      vertices.emplace_back(x + 50 * std::cos(k * std::numbers::pi / 3),
                            std::max(y + 50 * std::sin(k * std::numbers::pi / 3), 0.0));
    return Region::polygon(vertices);
  };
  double last = 0;
  for (int gap = 60; gap >= 0; gap -= 2) {
    SCOPED_TRACE(gap);
    const Lens lens{hexagon(gap + 50, 384), 3};
    const LensResult r = geometric.solve({lens});
    const double got = r.zoom_fits.at(0);
    EXPECT_FALSE(r.mesh_limited);
    EXPECT_GE(got, 1.5);
    if (gap < 60) EXPECT_LE(std::abs(got - last), 0.3);
    const TriangleDistortion measures = measure_triangles(r.warp);
    EXPECT_EQ(summarize(measures).flipped, 0);
    EXPECT_NEAR(measure_foci(r.warp, measures, {lens}).front().zoom, got, 3e-4);
    last = got;
  }
  EXPECT_NEAR(last, 3, 1e-9);
  // Touching the top side, dragged 4 px a step into the corner: it slides along the side (a
  // polygon did not, and fell to 1.0 a pixel from the left side), then the corner's ring.
  for (int x = 250; x >= 50; x -= 4) {
    SCOPED_TRACE(x);
    const LensResult r =
        geometric.solve({Lens{hexagon(x, 50 * std::sin(std::numbers::pi / 3)), 3}});
    const double got = r.zoom_fits.at(0);
    EXPECT_FALSE(r.mesh_limited);
    EXPECT_GE(got, 2);
    if (x < 250) EXPECT_LE(std::abs(got - last), 0.5);
    last = got;
  }
  EXPECT_NEAR(last, 3, 1e-9);
}

// An ellipse mask with a hole (semi-axes 50 x 30, the hole's 15 x 10: its pixel squares, no
// outline, so the mesh holds its focus sqrt 2 cells wider) at zoom 3 on 512 x 384 (mesh 60),
// dragged 1 px a step from 80 px to 2 px off the left side: its zoom changes by at most 0.05 a
// step and never falls below 1.3, the focus exact, nothing beyond the footprint moved. Its choice
// of rings near the side measured them without that band, so it chose the ring about its centre,
// which the fit then found 1.03 room for at 35 px, and sprang to 1.59 at 34 (the ring about the
// side's point).
TEST(FocusLens, AMaskWithAHoleNearingASideKeepsAContinuousZoom) {
  constexpr int kWidth = 512, kHeight = 384;
  LensOptions options;
  options.mesh = 60;
  const GeometricLens geometric(kWidth, kHeight, options);
  double last = 0;
  for (int gap = 80; gap >= 2; --gap) {
    SCOPED_TRACE(gap);
    Image mask(kWidth, kHeight, 1, 0);
    const Eigen::Vector2d c(gap + 50, 192);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const Eigen::Vector2d d = Eigen::Vector2d(x + 0.5, y + 0.5) - c;
        if (d.cwiseQuotient(Eigen::Vector2d(50, 30)).squaredNorm() < 1 &&
            d.cwiseQuotient(Eigen::Vector2d(15, 10)).squaredNorm() >= 1)
          mask.at(x, y)[0] = 255;
      }
    std::vector<Region> blobs = Region::from_mask(mask);
    ASSERT_EQ(blobs.size(), 1u);
    ASSERT_FALSE(blobs[0].outline());
    const Lens lens{std::move(blobs[0]), 3};
    const LensResult r = geometric.solve({lens});
    const double got = r.zoom_fits.at(0);
    EXPECT_GE(got, 1.3);
    if (gap < 80) EXPECT_LE(std::abs(got - last), 0.05);
    const TriangleDistortion measures = measure_triangles(r.warp);
    EXPECT_EQ(summarize(measures).flipped, 0);
    const FocusMeasure focus = measure_foci(r.warp, measures, {lens}).front();
    EXPECT_NEAR(focus.zoom, got, 1e-4 * got);
    EXPECT_LE(focus.uniformity, 1.0001);
    EXPECT_EQ(focus.displacement_beyond_footprint, 0);
    last = got;
  }
}

// A warp's scale along the ray from `origin` in unit direction `u` (source pixels): at t, the
// component along u of how far the points at t and t + step apart go, over step (5 px, a cell
// of the 400 grid, so that the mesh's piecewise linear steps do not count).
struct RayScale {
  const WarpMap& map;
  Eigen::Vector2d origin, u;
  double step = 5;
  double operator()(double t) const {
    const std::optional<Eigen::Vector2d> a = map.forward(origin + t * u),
                                         b = map.forward(origin + (t + step) * u);
    EXPECT_TRUE(a && b) << t;
    return a && b ? (*b - *a).dot(u) / step : 0.0;
  }
  // The largest change of the scale per pixel for t in [from, to), in 1 px steps.
  double largest_change(double from, double to) const {
    double worst = 0;
    for (double t = from; t < to; t += 1)
      worst = std::max(worst, std::abs((*this)(t + step) - (*this)(t)) / step);
    return worst;
  }
};

// The rim without a crease: along a ray from a circle's centre the radial scale reaches 1 at the
// footprint's edge continuously, changing by at most 0.02 a pixel across it at zooms 2 to 8
// (RayScale; 0.010 to 0.016 here), 0.95 or more over the last 6 px; the power ring's scale jumped
// from about k (0.39 at zoom 3, 0.25 at 8) to 1 within a pixel there. Its focus is still
// magnified exactly.
TEST(FocusLens, ItsRimEndsWithoutACrease) {
  LensOptions options;
  options.mesh = 400;
  const GeometricLens geometric(2048, 1350, options);
  for (double zoom = 2; zoom <= 8; zoom += 1) {
    SCOPED_TRACE(zoom);
    const Lens lens{Region::circle({1024, 675}, 50), zoom};
    const LensResult r = geometric.solve({lens});
    const WarpMap map(r.warp);
    const double edge = 50 * footprint_ratio(lens);
    for (const Eigen::Vector2d u : {Eigen::Vector2d(1, 0), Eigen::Vector2d(0.6, -0.8)}) {
      const RayScale scale{map, {1024, 675}, u};
      EXPECT_LE(scale.largest_change(0.5 * edge, edge + 20), 0.02);
      EXPECT_GT(scale(edge - scale.step - 1), 0.94);
      EXPECT_NEAR(scale(edge + 1), 1, 1e-6);
    }
    const TriangleDistortion measures = measure_triangles(r.warp);
    EXPECT_EQ(summarize(measures).flipped, 0);
    EXPECT_NEAR(measure_foci(r.warp, measures, {lens}).front().zoom,
                r.zoom_fits[0] < zoom ? r.zoom_fits[0] : zoom, 1e-3 * zoom);
  }
}

// A polygon's ring has the same rim: a paragraph-sized rectangle (268 x 174 px) at zoom 2, along
// the ray down from its centre (0.0055 a pixel at most; the power ring stepped by 0.09 a pixel
// over 5 px, from 0.54 inside its edge to 1).
TEST(FocusLens, APolygonsRimEndsWithoutACrease) {
  LensOptions options;
  options.mesh = 400;
  const Lens lens{Region::polygon({{358, 318}, {626, 318}, {626, 492}, {358, 492}}), 2};
  const LensResult r = GeometricLens(1024, 1024, options).solve({lens});
  const WarpMap map(r.warp);
  const RayScale scale{map, {492, 405}, {0, 1}};
  double edge = 0;  // the last point of the ray the lens moves
  for (double t = 100; t < 600; t += 1)
    if (std::abs(scale(t) - 1) > 1e-3) edge = t;
  EXPECT_GT(edge, 300);  // the footprint reaches that far below the centre
  EXPECT_LE(scale.largest_change(100, 600), 0.02);
  EXPECT_GT(scale(edge - 6), 0.97);
  EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0);
}

TEST(FocusLens, FootprintMustExceedTheZoom) {
  Lens lens{Region::circle({500, 500}, 50), 2.0};
  lens.footprint = 2.0;
  EXPECT_THROW(GeometricLens(1024, 1024).solve({lens}), InvalidInput);
  lens.footprint = 6.0;
  const LensResult r = GeometricLens(1024, 1024).solve({lens});
  EXPECT_NEAR(r.zoom_measured[0], 2.0, 0.05);
  // A wider footprint spreads the same compression thinner.
  lens.footprint = 3.0;
  const LensResult tight = GeometricLens(1024, 1024).solve({lens});
  EXPECT_LT(summarize(measure_triangles(r.warp)).conformal_max,
            summarize(measure_triangles(tight.warp)).conformal_max);
}

// The ring's contours are offset curves of the focus, rounded where a reflex corner's two edges
// are equally near (a crease there would show along the whole bisector): across the bisector of
// the L's reflex corner, 60 px out, the start's slope changes in proportion to the step it is
// measured over (its second difference: C1), where a crease kept a jump of 0.77.
TEST(FocusLens, StartHasNoCreaseAlongAReflexCornersBisector) {
  const Eigen::Vector2d middle(512, 512);
  const std::vector<Lens> lenses = {Lens{Region::polygon(translated(kL, middle)), 2}};
  const double cell = 1024.0 / 99;
  ThreadPool pool(1);
  const double band = focus_band(lenses, cell);
  const auto map = focus_map(lenses, focus_groups(lenses, 1024, 1024, {cell, band}), cell, band,
                             1024, 1024, pool);
  const Eigen::Vector2d corner = middle + Eigen::Vector2d(-40, 40);
  const Eigen::Vector2d out = Eigen::Vector2d(1, -1).normalized(), across(out.y(), -out.x());
  auto slope_jump = [&](double h) {
    Eigen::MatrixX2d q(3, 2);
    for (int k = 0; k < 3; ++k) q.row(k) = (corner + 60 * out + (k - 1) * h * across).transpose();
    const Eigen::MatrixX2d m = map(q);
    EXPECT_GT((m.row(1) - q.row(1)).norm(), 1.0);  // in the ring: moved
    return ((m.row(2) - m.row(1)) / h - (m.row(1) - m.row(0)) / h).norm();
  };
  const double coarse = slope_jump(0.01), fine = slope_jump(0.001);
  EXPECT_LT(coarse, 0.01);
  EXPECT_LT(fine, 0.2 * coarse) << coarse << " / " << fine;
}

// moved_focus_mesh's contract, on the benchmark's circle (its footprint cut on three sides) moved
// 3 px right and 2 px down: the focus's vertices move rigidly, those on the footprint's edge lie
// on the moved edge (or a thousandth of a cell inside the border, where the edge runs along it),
// those on an image side stay on it, and no triangle folds.
TEST(FocusLens, MovedMeshKeepsItsCurvesAndSides) {
  const Lens from{Region::circle({400, 512}, 150), 2}, to{Region::circle({403, 514}, 150), 2};
  const Grid grid = make_grid(1024, 1024, 100);
  const double band = focus_band({from}, grid.cell);
  std::vector<int> on_curve;
  const PlanarMesh mesh = conform_mesh(grid, focus_curves({from}, grid.cell, band, 1024, 1024),
                                       0.4 * grid.cell, {}, &on_curve);
  const Eigen::AlignedBox2d box(Eigen::Vector2d::Zero(), Eigen::Vector2d(1024, 1024));
  ThreadPool pool(1);
  const std::optional<Eigen::MatrixX2d> V = moved_focus_mesh(
      mesh, on_curve, {from}, box, grid.cell, {to}, box, grid.cell, 1024, 1024, pool);
  ASSERT_TRUE(V);
  const std::vector<MeshCurve> curves = focus_curves({to}, grid.cell, band, 1024, 1024);
  ASSERT_EQ(curves.size(), 2u);  // the circle, the footprint's edge
  int rim = 0, edge = 0;
  for (Eigen::Index i = 0; i < V->rows(); ++i) {
    const Eigen::Vector2d p = mesh.V.row(i), q = V->row(i);
    if (from.region.distance(p) == 0) {
      EXPECT_LT((q - p - Eigen::Vector2d(3, 2)).norm(), 1e-9) << i;
      rim += on_curve[size_t(i)] == 0;
    }
    if (on_curve[size_t(i)] == 1 && mesh.sides[size_t(i)] == 0) {
      const double border = std::min({q.x(), q.y(), 1024 - q.x(), 1024 - q.y()});
      if (border > 2e-3 * grid.cell) EXPECT_NEAR(curves[1].level(q), 0, 1e-6) << i;
      ++edge;
    }
    if (mesh.V(i, 0) == 0 || mesh.V(i, 0) == 1024) EXPECT_EQ(q.x(), mesh.V(i, 0)) << i;
    if (mesh.V(i, 1) == 0 || mesh.V(i, 1) == 1024) EXPECT_EQ(q.y(), mesh.V(i, 1)) << i;
  }
  EXPECT_GT(rim, 50);
  EXPECT_GT(edge, 50);
  EXPECT_EQ(count_folds(*V, mesh.F), 0);
}

// A lens dragged with its footprint cut by the image border: its mesh moves with it, deformed
// where the border bends the ring, for kMovedMeshDrift (1.5) cells before it is made anew,
// instead of being made anew each frame. Its picture stays within half a pixel of a 4x finer
// solve's (as FinerMesh asks of a fresh mesh), and within a fifth of a pixel of the fresh mesh's
// own gap to it, at frames moved 10 to 15 px from where the mesh was made (3 px a frame: frames
// 4 and 5; 10 px: 1 and 5). With 2 cells of drift the circle dragged 10 px a frame reached 0.41
// against the fresh mesh's 0.18; with 3, 1.6 px.
struct Drag {
  const char* name;
  std::function<Region(double x)> region;
  double zoom, step;
};
class DraggedAlongTheBorder : public testing::TestWithParam<Drag> {};

// The largest and the mean distance between where two warps of a 1024 px image put the points
// `step` px apart (from step / 2).
struct WarpGap {
  double worst = 0, mean = 0;
};
WarpGap warp_gap(const WarpMesh& a, const WarpMesh& b, double step) {
  const WarpMap map_a(a), map_b(b);
  WarpGap gap;
  int count = 0;
  for (double y = step / 2; y < 1024; y += step) {
    for (double x = step / 2; x < 1024; x += step) {
      const std::optional<Eigen::Vector2d> pa = map_a.forward({x, y}), pb = map_b.forward({x, y});
      EXPECT_TRUE(pa && pb) << x << ", " << y;
      if (!pa || !pb) continue;
      gap.worst = std::max(gap.worst, (*pa - *pb).norm());
      gap.mean += (*pa - *pb).norm();
      ++count;
    }
  }
  gap.mean /= count;
  return gap;
}

TEST_P(DraggedAlongTheBorder, MovedMeshDrawsWhatAFreshMeshDraws) {
  LensSession session(1024, 1024);
  LensOptions fine_options;
  fine_options.mesh = 400;
  const GeometricLens fresh(1024, 1024), fine(1024, 1024, fine_options);
  for (int frame = 0; frame <= 5; ++frame) {
    const Lens lens{GetParam().region(400 + GetParam().step * frame), GetParam().zoom};
    const LensResult moved = session.update({lens});
    SCOPED_TRACE(frame);
    ASSERT_EQ(summarize(measure_triangles(moved.warp)).flipped, 0);
    if (frame != 1 && frame != 4 && frame != 5) continue;
    const WarpMesh truth = fine.solve({lens}).warp;
    const double gap = warp_gap(moved.warp, truth, 8).worst;
    EXPECT_LT(gap, 0.5);
    EXPECT_LT(gap, warp_gap(fresh.solve({lens}).warp, truth, 8).worst + 0.2);
  }
}

INSTANTIATE_TEST_SUITE_P(
    FocusLens, DraggedAlongTheBorder,
    testing::Values(Drag{"circle",
                         [](double x) {
                           return Region::circle({x, 512}, 150);
                         },
                         2, 3},
                    Drag{"circle_fast",
                         [](double x) {
                           return Region::circle({x, 512}, 150);
                         },
                         2, 10},
                    Drag{"star",
                         [](double x) {
                           return Region::polygon(translated(star(), {x, 512}));
                         },
                         2.5, 3},
                    Drag{"near_side",
                         [](double x) {
                           return Region::circle({x, 120}, 80);
                         },
                         2, 3},
                    // over the top side: magnified about a point on it
                    Drag{"over_side",
                         [](double x) {
                           return Region::circle({x, 40}, 80);
                         },
                         2, 3}),
    [](const testing::TestParamInfo<Drag>& info) { return std::string(info.param.name); });

// The interactive path: a dragged focus lens keeps its zoom and uniform focus every frame.
TEST(FocusLens, UpdateFollowsADraggedLens) {
  LensSession geometric(1024, 1024);
  for (int step = 0; step < 6; ++step) {
    const Lens lens{Region::circle({440.0 + 12 * step, 500.0 + 5 * step}, 80), 2.0};
    const LensResult r = geometric.update({lens});
    const FocusMeasure f = measure_foci(r.warp, measure_triangles(r.warp), {lens}).front();
    SCOPED_TRACE(step);
    EXPECT_NEAR(f.zoom, 2.0, 0.1);
    EXPECT_LE(f.uniformity, 1.1);
    EXPECT_EQ(f.displacement_beyond_footprint, 0.0);
    EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0);
  }
}

}  // namespace
}  // namespace geolens

namespace geolens {
namespace {

// Lenses whose magnified foci would overlap are magnified together, as one similarity: both
// regions at the larger zoom, and the distance between them magnified by it too.
TEST(FocusLens, OverlappingFociAreMagnifiedTogether) {
  const std::vector<Lens> lenses = {Lens{Region::circle({900, 1000}, 80), 2.0},
                                    Lens{Region::circle({1100, 1000}, 80), 2.5}};
  const LensResult r = GeometricLens(2000, 2000).solve(lenses);
  const std::vector<FocusMeasure> f = measure_foci(r.warp, measure_triangles(r.warp), lenses);
  for (const FocusMeasure& m : f) {
    EXPECT_NEAR(m.zoom, 2.5, 0.05);
    EXPECT_LE(m.uniformity, 1.1);
  }
  // The two centres move apart by the zoom: the union is one magnified picture.
  auto screen_of = [&](const Eigen::Vector2d& p) {
    Eigen::Index nearest;
    (r.warp.source.rowwise() - p.transpose()).rowwise().squaredNorm().minCoeff(&nearest);
    return Eigen::Vector2d(r.warp.screen.row(nearest).transpose());
  };
  EXPECT_NEAR((screen_of({1100, 1000}) - screen_of({900, 1000})).norm(), 2.5 * 200, 2.5 * 10);
}

// Two lenses moved towards each other (issue 28, item 4), 1 px a step on the 512 px image until
// their regions are 2 px apart: apart, the room between them is shared (both at one level of log
// zoom, each at most its own), and they are magnified as one where that gives both at least as
// much, so neither zoom jumps (on main before: 0.26 to 1.43 in one step, where they merged) and
// neither falls below 2, which each fits alone (1.21 to 1.74 before). A lens asked less than
// its neighbour steps up to the merged zoom (0.06 here).
TEST(FocusLens, TwoLensesMovedTogetherShareTheRoomWithoutAJump) {
  struct Pair {
    double r1, z1, r2, z2;
  };
  const GeometricLens lens(512, 512);
  for (const Pair& p : {Pair{30, 2, 30, 2}, Pair{30, 4, 25, 3}, Pair{40, 3, 20, 2}}) {
    SCOPED_TRACE(testing::Message()
                 << "r " << p.r1 << " at " << p.z1 << ", r " << p.r2 << " at " << p.z2);
    std::vector<double> before;
    double worst = 0, least = kMaxZoom;
    for (double d = 220; d >= p.r1 + p.r2 + 2; --d) {
      const LensResult r = lens.solve({Lens{Region::circle({256 - d / 2, 256}, p.r1), p.z1},
                                       Lens{Region::circle({256 + d / 2, 256}, p.r2), p.z2}});
      for (size_t k = 0; k < 2; ++k) {
        if (!before.empty()) worst = std::max(worst, std::abs(r.zoom_fits[k] - before[k]));
        least = std::min(least, r.zoom_fits[k]);
      }
      before = r.zoom_fits;
    }
    EXPECT_LE(worst, 0.07);
    EXPECT_GE(least, 2 - 1e-6);
  }
}

// Small circles far apart share one mesh over the box of their footprints, of 4.9 px cells
// here: circles of 2 cells are followed by it, so each gets its zoom and is magnified exactly
// (both were shown unmagnified when circles below 3 cells were not followed).
TEST(FocusLens, SmallCirclesFarApartGetTheirZoom) {
  const std::vector<Lens> lenses = {Lens{Region::circle({56, 256}, 10), 2},
                                    Lens{Region::circle({456, 256}, 10), 2}};
  const LensResult r = GeometricLens(512, 512).solve(lenses);
  const std::vector<FocusMeasure> f = measure_foci(r.warp, measure_triangles(r.warp), lenses);
  for (size_t k : {0, 1}) {
    EXPECT_DOUBLE_EQ(r.zoom_fits[k], 2);
    EXPECT_NEAR(f[k].zoom, 2, 0.02);
    EXPECT_LE(f[k].uniformity, 1.01);
  }
}

// A small circle beside a large lens far from it: the box of both footprints sets a mesh of 10 px
// cells, too coarse to follow the small one, so the grid is made finer for it (up to twice, 5 px
// cells) and it gets its zoom at every radius from 11 px up, magnified exactly; below that the
// mesh is said to limit it (it was shown unmagnified up to r 15, told "its footprint"). A
// session's draft on the 50 grid, too coarse for it, is solved finer: a drag shows the zoom too.
TEST(FocusLens, ASmallCircleBesideALargeLensGetsItsZoom) {
  const GeometricLens lens(1024, 1024);
  for (double r = 11; r <= 30; r += 1) {
    const std::vector<Lens> lenses = {Lens{Region::circle({300, 300}, 200), 2},
                                      Lens{Region::circle({850, 850}, r), 3}};
    const LensResult result = lens.solve(lenses);
    EXPECT_DOUBLE_EQ(result.zoom_fits[1], 3) << r;
    EXPECT_TRUE(result.zoom_fit_reasons[1].empty()) << r << ": " << result.zoom_fit_reasons[1];
    const TriangleDistortion measures = measure_triangles(result.warp);
    EXPECT_EQ(summarize(measures).flipped, 0) << r;
    const FocusMeasure f = measure_foci(result.warp, measures, lenses)[1];
    EXPECT_NEAR(f.zoom, 3, 0.03) << r;
    EXPECT_LE(f.uniformity, 1.01) << r;
  }
  const std::vector<Lens> tiny = {Lens{Region::circle({300, 300}, 200), 2},
                                  Lens{Region::circle({850, 850}, 8), 3}};
  const LensResult r = lens.solve(tiny);
  EXPECT_LT(r.zoom_fits[1], 3);
  EXPECT_EQ(r.zoom_fit_reasons[1], "the mesh (a finer mesh fits more)");
  EXPECT_TRUE(r.mesh_limited);
  LensOptions options;
  options.draft_mesh = 50;
  LensSession session(1024, 1024, options);
  const std::vector<Lens> lenses = {Lens{Region::circle({300, 300}, 200), 2},
                                    Lens{Region::circle({850, 850}, 15), 3}};
  EXPECT_DOUBLE_EQ(session.update(lenses, {}, true).zoom_fits[1], 3);
}

// The robustness sweep: 1000 seeded setups on a 512 px image, 1 to 6 lenses of radius 5
// to 400 px and zoom 1 to 8 anywhere (corners, borders, centre), overlapping or not. No triangle
// flips, no focus is shrunk, and every lens that fits where it is and whose ring at the zoom
// asked meets no other's (a group of one) reaches its zoom (or the largest that fits there) over
// its whole region.
TEST(FocusLens, ThousandRandomSetups) {
  std::mt19937 random(20261129);
  std::uniform_real_distribution<double> unit(0, 1);
  int flipped = 0, shrunk = 0, missed = 0, alone = 0;
  LensOptions options;
  options.mesh = 50;
  for (int setup = 0; setup < 1000; ++setup) {
    std::vector<Lens> lenses;
    const int count = 1 + int(unit(random) * 6);
    for (int k = 0; k < count; ++k) {
      // A third of the centres on a corner or a side.
      Eigen::Vector2d c(unit(random) * 512, unit(random) * 512);
      const double where = unit(random);
      if (where < 0.15)
        c = Eigen::Vector2d(unit(random) < 0.5 ? 0 : 512, unit(random) < 0.5 ? 0 : 512);
      else if (where < 0.33)
        c.x() = unit(random) < 0.5 ? 0 : 512;
      const double radius = 5 + std::pow(unit(random), 3) * 395;  // small ones more often
      lenses.push_back(Lens{Region::circle(c, radius), 1 + unit(random) * 7});
    }
    const LensResult r = GeometricLens(512, 512, options).solve(lenses);
    const TriangleDistortion measures = measure_triangles(r.warp);
    const std::vector<FocusMeasure> f = measure_foci(r.warp, measures, lenses);
    std::string described;  // the setup as geolens's --lens options
    for (const Lens& l : lenses)
      described += " --lens circle:" + std::to_string(l.region.peak().x()) + "," +
                   std::to_string(l.region.peak().y()) + "," + std::to_string(l.region.size()) +
                   ":" + std::to_string(l.zoom);
    if (const int folds = summarize(measures).flipped; folds > 0) {
      flipped += folds;
      ADD_FAILURE() << "setup " << setup << ": " << folds << " flipped," << described;
    }
    std::vector<double> log_zooms;
    for (const Lens& lens : lenses) log_zooms.push_back(std::log(lens.zoom));
    for (const FocusGroup& g : focus_groups(lenses, log_zooms, 512, 512, FitMesh{})) {
      for (size_t k : g.lenses) {
        if (f[k].zoom < 1 - 1e-6) {
          ++shrunk;
          ADD_FAILURE() << "setup " << setup << " lens " << k << " shrunk to " << f[k].zoom
                        << " (fit " << r.zoom_fits[k] << ", centre "
                        << lenses[k].region.peak().transpose() << ", radius "
                        << lenses[k].region.size() << ")";
        }
        if (g.lenses.size() > 1) continue;
        // A lens that does not fit is solved at the largest zoom that does.
        const double zoom = std::min(lenses[k].zoom, std::max(1.0, r.zoom_fits[k]));
        alone += zoom == lenses[k].zoom;
        if (std::abs(f[k].zoom / zoom - 1) > 0.05) {
          ++missed;
          ADD_FAILURE() << "setup " << setup << " lens " << k << " zoom " << zoom << " measured "
                        << f[k].zoom << described;
        }
      }
    }
  }
  EXPECT_EQ(flipped, 0);
  EXPECT_EQ(shrunk, 0);
  EXPECT_EQ(missed, 0);
  // Most lenses of these sizes and zooms do not fit on a 512 px image where they are (and are
  // solved at the largest zoom that does); these many do and reach the zoom asked.
  EXPECT_GE(alone, 20);
}

}  // namespace
}  // namespace geolens

namespace geolens {
namespace {

// The picture does not depend on the mesh (issue 13): a lens on the 100 grid sends every source
// point of a 1024 px image where the same lens on a 4x finer grid sends it within 0.5 px. The
// grid follows every region's boundary and every footprint's edge (conform_mesh) and is refined
// where the start strays from linear by more than 0.2 px. Measured (zoom 2, 3, 4): the L
// 0.22 / 0.23 / 0.23 px, the 10:1 strip 0.20 / 0.21 / 0.21, the star 0.25 / 0.24 / 0.23, a circle
// at the centre 0.14 / 0.21 / 0.19, a circle whose footprint the border cuts 0.18 / 0.18 / 0.21,
// a mask blob (an ellipse with a bite; its smoothed outline, Region::from_mask) 0.25 / 0.25 at
// zoom 2 / 3 (fitting 2 and 2.99); before: 24, 15, 22, 0.19, 1.4 and 22 px at zoom 2.
// The largest and the mean distance between where the lens on the 100 and on the 400 grid
// send the source points of a 4 px lattice of a 1024 px image; and the zooms each fitted.
struct MeshGap {
  double worst = 0, mean = 0, fit_coarse = 0, fit_fine = 0;
};
MeshGap finer_mesh_gap(const Lens& lens) {
  LensOptions coarse, fine;
  coarse.mesh = 100;
  fine.mesh = 400;
  const LensResult a = GeometricLens(1024, 1024, coarse).solve({lens});
  const LensResult b = GeometricLens(1024, 1024, fine).solve({lens});
  const WarpGap gap = warp_gap(a.warp, b.warp, 4);
  return MeshGap{gap.worst, gap.mean, a.zoom_fits[0], b.zoom_fits[0]};
}

struct FinerCase {
  const char* name;
  Lens lens;
  double fits = 0;  // the zoom that fits (measured on both grids), to 0.5 %
};
class FinerMesh : public testing::TestWithParam<FinerCase> {};

TEST_P(FinerMesh, MovesNoPointByHalfAPixel) {
  const MeshGap gap = finer_mesh_gap(GetParam().lens);
  EXPECT_NEAR(gap.fit_coarse / GetParam().fits, 1.0, 0.005);
  EXPECT_NEAR(gap.fit_coarse / gap.fit_fine, 1.0, 0.002);
  EXPECT_LT(gap.worst, 0.5);
  EXPECT_LT(gap.mean, 0.05);
}

const Eigen::Vector2d kMiddle(512, 512);
// A mask blob: an ellipse with a bite out of it, 1024 px image.
Region blob_mask() {
  Image mask(1024, 1024, 1, 0);
  for (int y = 0; y < 1024; ++y)
    for (int x = 0; x < 1024; ++x) {
      const double u = (x + 0.5 - 512) / 120, v = (y + 0.5 - 512) / 80;
      const double bite = std::hypot(x + 0.5 - 620, y + 0.5 - 560);
      if (u * u + v * v <= 1 && bite > 50) mask.at(x, y)[0] = 255;
    }
  return Region::from_mask(mask).front();
}
INSTANTIATE_TEST_SUITE_P(
    FocusLens, FinerMesh,
    testing::Values(FinerCase{"L", Lens{Region::polygon(translated(kL, kMiddle)), 2}, 2},
                    FinerCase{"L3", Lens{Region::polygon(translated(kL, kMiddle)), 3}, 2.69},
                    FinerCase{"strip", Lens{Region::polygon(translated(kStrip, kMiddle)), 2}, 2},
                    FinerCase{"star", Lens{Region::polygon(translated(star(), kMiddle)), 2}, 2},
                    FinerCase{"circle4", Lens{Region::circle(kMiddle, 100), 4}, 3.69},
                    // its footprint cut by the image's side
                    FinerCase{"side", Lens{Region::circle({300, 80}, 100), 2}, 2},
                    FinerCase{"mask", Lens{blob_mask(), 2}, 2},
                    FinerCase{"mask3", Lens{blob_mask(), 3}, 2.99}),
    [](const testing::TestParamInfo<FinerCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace geolens

namespace geolens {
namespace {

// The trade-off: at every footprint the focus lens stays within 1.3 times the radial bound (1.20
// and 1.23 here; 1.24 and 1.32 before the mesh was refined by its slope next to the focus) and
// 12 % of its ring's (the rim's, at most 1.15 times the radial bound: rim_distortion_bound), below
// every classic lens with a uniform focus but the bound-reaching power ring (within 5 % of the
// bound on a 400 grid for the classic lenses; 7 % on the 200 grid), and its focus is uniform.
TEST(FootprintSweep, FocusLensAgainstTheBoundAndTheClassicLenses) {
  LensOptions options;
  options.mesh = 200;
  const Lens lens{Region::circle({256, 256}, 25), 2.0};
  const Sweep sweep = footprint_sweep(512, 512, lens, options, {4, 8}, 400);
  ASSERT_EQ(sweep.ratios.size(), 2u);
  ASSERT_EQ(sweep.points.size(), 2 * (1 + kClassicLenses.size()));
  for (size_t i = 0; i < sweep.ratios.size(); ++i) {
    SCOPED_TRACE(sweep.ratios[i]);
    auto at = [&](const std::string& method) {
      for (const SweepPoint& p : sweep.points)
        if (p.method == method && p.ratio == sweep.ratios[i]) return p;
      ADD_FAILURE() << method << " missing";
      return SweepPoint{};
    };
    const SweepPoint geometric = at("geometric");
    EXPECT_NEAR(geometric.zoom, 2.0, 0.02);
    EXPECT_LE(geometric.uniformity, 1.01);
    EXPECT_NEAR(sweep.bound[i], radial_distortion_bound(geometric.zoom, sweep.ratios[i]), 1e-12);
    EXPECT_NEAR(sweep.rim_bound[i], rim_distortion_bound(geometric.zoom, sweep.ratios[i]), 1e-12);
    EXPECT_LE(geometric.shape_max, 1.3 * sweep.bound[i]);
    EXPECT_LE(geometric.shape_max, 1.12 * sweep.rim_bound[i]);
    EXPECT_NEAR(at("power_ring").shape_max / sweep.bound[i], 1.0, 0.05);
    for (const char* flat : {"bifocal", "flattop_linear", "flattop_cosine"}) {
      EXPECT_LE(at(flat).uniformity, 1.01) << flat;
      EXPECT_LT(geometric.shape_max, at(flat).shape_max) << flat;
    }
  }
  const Image plot = plot_sweep(sweep);
  EXPECT_EQ(plot.width, 720);
  EXPECT_EQ(plot.channels, 3);
  EXPECT_THROW(footprint_sweep(512, 512, lens, options, {1.5}), InvalidInput);  // not > zoom
}

// At zoom 3 over the sweep's footprints, the extremes of docs/reproduction's table, on a focus of
// 20 px: the mesh is refined relative to the region's size too (at a 0.2 px tolerance alone the
// largest footprint measured 1.26 times the bound), and by its slope next to the focus (without:
// 1.19 times the ring's bound at ratio 4; 1.09 with).
TEST(FootprintSweep, FocusLensNearTheBoundAtZoomThree) {
  LensOptions options;
  options.mesh = 200;
  const Lens lens{Region::circle({256, 256}, 20), 3.0};
  const Sweep sweep = footprint_sweep(512, 512, lens, options, {4, 12}, 50);
  int found = 0;
  for (size_t i = 0; i < sweep.ratios.size(); ++i) {
    SCOPED_TRACE(sweep.ratios[i]);
    for (const SweepPoint& p : sweep.points) {
      if (p.method != "geometric" || p.ratio != sweep.ratios[i]) continue;
      ++found;
      EXPECT_NEAR(p.zoom, 3.0, 0.03);
      EXPECT_LE(p.uniformity, 1.01);
      EXPECT_LE(p.shape_max, 1.3 * sweep.bound[i]);
      EXPECT_LE(p.shape_max, 1.12 * sweep.rim_bound[i]);
      EXPECT_GE(p.shape_max, sweep.bound[i] * (1 - 1e-9));  // no radial lens does better
    }
  }
  EXPECT_EQ(found, 2);
}

}  // namespace
}  // namespace geolens

namespace geolens {
namespace {

// A kind of region the library does not know: two regions taken as one (a multipolygon), written
// here against RegionShape alone.
class Pair final : public RegionShape {
 public:
  Pair(Region a, Region b) : a_(std::move(a)), b_(std::move(b)) {}
  std::string kind() const override { return "pair"; }
  Eigen::AlignedBox2d bounds() const override { return a_.bounds().merged(b_.bounds()); }
  Eigen::Vector2d peak() const override { return larger().peak(); }
  double size() const override { return larger().size(); }
  double reach() const override {
    const Region& l = larger();
    const Region& o = &l == &a_ ? b_ : a_;
    return std::max(l.reach(), (o.peak() - l.peak()).norm() + o.reach());
  }
  double depth(const Eigen::Vector2d& p) const override {
    return std::max(a_.depth(p), b_.depth(p));
  }
  double thickness(const Eigen::Vector2d& p) const override {
    return a_.depth(p) >= b_.depth(p) ? a_.thickness(p) : b_.thickness(p);
  }
  double distance(const Eigen::Vector2d& p) const override {
    return std::min(a_.distance(p), b_.distance(p));
  }
  std::vector<Eigen::Vector2d> anchors() const override {
    std::vector<Eigen::Vector2d> all = a_.anchors();
    for (const Eigen::Vector2d& v : b_.anchors()) all.push_back(v);
    return all;
  }

 private:
  const Region& larger() const { return a_.size() >= b_.size() ? a_ : b_; }
  Region a_, b_;
};

// Both parts of the pair are magnified as one focus, uniformly, by the zoom asked, with nothing
// folded: no switch in the library had to learn the new kind.
TEST(FocusLens, ARegionKindFromOutsideTheLibraryIsMagnifiedAsAWhole) {
  auto square = [](double x, double y, double side) {
    return Region::polygon({{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}});
  };
  const Region pair(std::make_shared<Pair>(square(380, 420, 110), square(540, 440, 90)));
  EXPECT_EQ(pair.kind(), "pair");
  EXPECT_EQ(pair.anchors().size(), 8u);
  const Lens lens{pair, 2.0};
  const LensResult r = GeometricLens(1024, 1024).solve({lens});
  const TriangleDistortion measures = measure_triangles(r.warp);
  const FocusMeasure f = measure_foci(r.warp, measures, {lens}).front();
  EXPECT_NEAR(f.zoom, 2.0, 0.1);
  EXPECT_LE(f.uniformity, 1.15);
  EXPECT_EQ(summarize(measures).flipped, 0);
  // A vertex outside the image is refused like a polygon's.
  const Region off(std::make_shared<Pair>(square(380, 420, 110), square(990, 440, 90)));
  EXPECT_THROW(GeometricLens(1024, 1024).solve({Lens{off, 2.0}}), InvalidInput);
}

}  // namespace
}  // namespace geolens
