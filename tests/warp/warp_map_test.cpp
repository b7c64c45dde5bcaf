// Points mapped through a WarpMesh: forward and inverse undo each other on every lens, agree
// with a linear scan, and say "nowhere" outside the covered area.

#include "geolens/warp/warp_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/lens/geometric_lens.h"

namespace geolens {
namespace {

// n points uniform over [0, width) x [0, height), seeded.
Eigen::MatrixX2d random_points(int n, double width, double height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(0, width), y(0, height);
  Eigen::MatrixX2d P(n, 2);
  for (int i = 0; i < n; ++i) P.row(i) << x(rng), y(rng);
  return P;
}

struct RoundTrip {
  int undefined = 0;  // points the first map sends nowhere
  double worst = 0;   // largest |back(there(p)) - p| over the others, pixels
};

// there(p), then back: forward then inverse (or inverse then forward) of every row of P.
template <typename There, typename Back>
RoundTrip round_trip(const Eigen::MatrixX2d& P, There there, Back back) {
  RoundTrip r;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Vector2d p = P.row(i).transpose();
    const std::optional<Eigen::Vector2d> q = there(p);
    if (!q) {
      ++r.undefined;
      continue;
    }
    const std::optional<Eigen::Vector2d> p2 = back(*q);
    r.worst = std::max(r.worst, p2 ? (*p2 - p).norm() : std::numeric_limits<double>::infinity());
  }
  return r;
}

RoundTrip source_round_trip(const WarpMap& map, const Eigen::MatrixX2d& P) {
  return round_trip(
      P, [&](const Eigen::Vector2d& p) { return map.forward(p); },
      [&](const Eigen::Vector2d& q) { return map.inverse(q); });
}

RoundTrip screen_round_trip(const WarpMap& map, const Eigen::MatrixX2d& Q) {
  return round_trip(
      Q, [&](const Eigen::Vector2d& q) { return map.inverse(q); },
      [&](const Eigen::Vector2d& p) { return map.forward(p); });
}

constexpr int kPoints = 100000;

// The geometric lens covers the whole image on both sides: every point maps, and back.
void expect_exact_round_trips(const WarpMesh& warp, double width, double height) {
  const WarpMap map(warp);
  const RoundTrip source = source_round_trip(map, random_points(kPoints, width, height, 1));
  EXPECT_EQ(source.undefined, 0);
  EXPECT_LT(source.worst, 1e-6);
  const RoundTrip screen = screen_round_trip(map, random_points(kPoints, width, height, 2));
  EXPECT_EQ(screen.undefined, 0);
  EXPECT_LT(screen.worst, 1e-6);
}

TEST(WarpMap, RoundTripsThroughTheGeometricLens) {
  const LensResult r =
      GeometricLens(1024, 1024).solve({Lens{Region::circle({512, 512}, 150), 2.0}});
  ASSERT_EQ(r.model, LensModel::kFocus);
  expect_exact_round_trips(r.warp, 1024, 1024);
}

// The lift model: its source is the harmonic texture, not the grid, and its border slides.
TEST(WarpMap, RoundTripsThroughTheLiftModel) {
  LensOptions options;
  options.model = LensModel::kLift;
  const LensResult r =
      GeometricLens(1024, 768, options).solve({Lens{Region::circle({400, 380}, 120), 2.0}});
  expect_exact_round_trips(r.warp, 1024, 768);
}

TEST(WarpMap, RoundTripsThroughAPolygonLens) {
  std::vector<Eigen::Vector2d> star;
  for (int k = 0; k < 10; ++k) {
    const double radius = k % 2 == 0 ? 120 : 46,
                 a = std::numbers::pi / 2 + k * std::numbers::pi / 5;
    star.emplace_back(512 + radius * std::cos(a), 512 - radius * std::sin(a));
  }
  const LensResult r = GeometricLens(1024, 1024).solve({Lens{Region::polygon(star), 2.5}});
  expect_exact_round_trips(r.warp, 1024, 1024);
}

// Every classic lens maps every point both ways but the zoom-in lens, whose hidden ring
// r / z < |p - c| < r is shown nowhere: exactly those source points map nowhere (1 px margins
// for the rims, which the mesh follows with chords).
TEST(WarpMap, RoundTripsThroughEveryClassicLens) {
  const CircleLens lens{{300, 260}, 150, 2.0};
  const Eigen::MatrixX2d P = random_points(kPoints, 640, 480, 3);
  const Eigen::MatrixX2d Q = random_points(kPoints, 640, 480, 4);
  for (const ClassicLens kind : kClassicLenses) {
    SCOPED_TRACE(to_string(kind));
    const WarpMap map(classic_warp(kind, {lens}, 640, 480));
    const RoundTrip screen = screen_round_trip(map, Q);
    EXPECT_EQ(screen.undefined, 0);
    EXPECT_LT(screen.worst, 1e-6);
    const RoundTrip source = source_round_trip(map, P);
    EXPECT_LT(source.worst, 1e-6);
    if (kind != ClassicLens::kZoomIn) {
      EXPECT_EQ(source.undefined, 0);
      continue;
    }
    int hidden = 0, misplaced = 0;
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const double d = (Eigen::Vector2d(P.row(i).transpose()) - lens.center).norm();
      const bool in_ring = d > lens.radius / lens.zoom + 1 && d < lens.radius - 1;
      const bool near_rim =
          std::abs(d - lens.radius / lens.zoom) <= 1 || std::abs(d - lens.radius) <= 1;
      if (near_rim) continue;
      const bool mapped = map.forward(P.row(i).transpose()).has_value();
      hidden += in_ring;
      misplaced += mapped == in_ring;
    }
    EXPECT_GT(hidden, 10000);  // 3 / 4 of the disk: 17 % of the image
    EXPECT_EQ(misplaced, 0);
  }
}

// The point-in-triangle reference: every triangle tested in order, no index, no tolerance.
// The triangle that holds p and p's image, or -1.
std::pair<Eigen::Index, Eigen::Vector2d> linear_scan(const WarpMesh& warp,
                                                     const Eigen::Vector2d& p) {
  for (Eigen::Index f = 0; f < warp.F.rows(); ++f) {
    const Eigen::Vector2d a = warp.source.row(warp.F(f, 0)), b = warp.source.row(warp.F(f, 1)),
                          c = warp.source.row(warp.F(f, 2));
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (area == 0) continue;
    auto cross = [&](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
      return ((v - u).x() * (p - u).y() - (v - u).y() * (p - u).x()) / area;
    };
    const double wa = cross(b, c), wb = cross(c, a), wc = cross(a, b);
    if (wa < 0 || wb < 0 || wc < 0) continue;
    return {f, wa * Eigen::Vector2d(warp.screen.row(warp.F(f, 0))) +
                   wb * Eigen::Vector2d(warp.screen.row(warp.F(f, 1))) +
                   wc * Eigen::Vector2d(warp.screen.row(warp.F(f, 2)))};
  }
  return {-1, Eigen::Vector2d::Zero()};
}

TEST(WarpMap, ForwardAgreesWithALinearScan) {
  const LensResult r =
      GeometricLens(1024, 1024).solve({Lens{Region::circle({600, 450}, 120), 2.0}});
  const WarpMesh zoom_in =
      classic_warp(ClassicLens::kZoomIn, {{{512, 512}, 150, 3.0}}, 1024, 1024, 100);
  for (const WarpMesh* warp : {&r.warp, &zoom_in}) {
    const WarpMap map(*warp);
    // Over the image and a band around it, where nothing maps.
    Eigen::MatrixX2d P = random_points(2000, 1224, 1224, 5);
    P.array() -= 100;
    const Eigen::MatrixX2d batch = map.forward_batch(P);
    int mapped = 0;
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const Eigen::Vector2d p = P.row(i).transpose();
      const auto [f, expected] = linear_scan(*warp, p);
      const std::optional<Eigen::Vector2d> got = map.forward(p);
      ASSERT_EQ(got.has_value(), f >= 0) << p.transpose();
      EXPECT_EQ(map.source_triangle(p), f);
      if (!got) {
        EXPECT_TRUE(batch.row(i).array().isNaN().all());
        continue;
      }
      ++mapped;
      EXPECT_LT((*got - expected).norm(), 1e-9) << p.transpose();
      EXPECT_EQ(Eigen::Vector2d(batch.row(i).transpose()), *got);
    }
    EXPECT_GT(mapped, 1000);
    // On the mesh's vertices, each on the edges of several triangles, the same (first) one.
    for (Eigen::Index v = 0; v < warp->source.rows(); v += 5) {
      const Eigen::Vector2d p = warp->source.row(v).transpose();
      EXPECT_EQ(map.source_triangle(p), linear_scan(*warp, p).first) << p.transpose();
    }
  }
}

// Outside the covered area: empty for single points, NaN rows for batches, in both directions;
// the mesh's own border and shared edges still map.
TEST(WarpMap, OutsideTheCoveredAreaIsNowhere) {
  const LensResult r = GeometricLens(800, 600).solve({Lens{Region::circle({400, 300}, 100), 2.0}});
  const WarpMap map(r.warp);
  const std::vector<Eigen::Vector2d> outside = {{-0.5, 300},   {800.5, 300}, {400, -1e-3},
                                                {400, 600.01}, {-1e9, 1e9},  {1e300, 0}};
  Eigen::MatrixX2d P(Eigen::Index(outside.size()), 2);
  for (size_t i = 0; i < outside.size(); ++i) {
    EXPECT_FALSE(map.forward(outside[i])) << outside[i].transpose();
    EXPECT_FALSE(map.inverse(outside[i])) << outside[i].transpose();
    EXPECT_EQ(map.source_triangle(outside[i]), -1);
    EXPECT_EQ(map.screen_triangle(outside[i]), -1);
    P.row(Eigen::Index(i)) = outside[i].transpose();
  }
  EXPECT_TRUE(map.forward_batch(P).array().isNaN().all());
  EXPECT_TRUE(map.inverse_batch(P).array().isNaN().all());
  // A batch's NaN rows chain into the next batch: nowhere stays nowhere, the rest maps back.
  Eigen::MatrixX2d mixed(2, 2);
  mixed << 400, 300, -0.5, 300;
  const Eigen::MatrixX2d back = map.inverse_batch(map.forward_batch(mixed));
  EXPECT_LT((back.row(0) - mixed.row(0)).norm(), 1e-9);
  EXPECT_TRUE(back.row(1).array().isNaN().all());
  // The image's corners and sides, and every mesh vertex (on the edges of its triangles).
  for (const Eigen::Vector2d& p : std::vector<Eigen::Vector2d>{
           {0, 0}, {800, 0}, {800, 600}, {0, 600}, {0, 123.4}, {800, 456.7}, {321.5, 600}}) {
    ASSERT_TRUE(map.forward(p)) << p.transpose();
    EXPECT_LT((*map.forward(p) - p).norm(), 1e-9);  // the focus lens leaves the border in place
    EXPECT_TRUE(map.inverse(p)) << p.transpose();
  }
  const Eigen::MatrixX2d screen = map.forward_batch(r.warp.source);
  EXPECT_FALSE(screen.array().isNaN().any());
  EXPECT_LT((screen - r.warp.screen).cwiseAbs().maxCoeff(), 1e-9);
  const Eigen::MatrixX2d source = map.inverse_batch(r.warp.screen);
  EXPECT_FALSE(source.array().isNaN().any());
  EXPECT_LT((source - r.warp.source).cwiseAbs().maxCoeff(), 1e-9);
  // An empty batch is an empty answer.
  EXPECT_EQ(map.forward_batch(Eigen::MatrixX2d(0, 2)).rows(), 0);
}

// Two triangles over the unit square and, listed first, a third whose screen is folded back
// over them: the inverse returns the preimage in the folded one (the first that holds the
// point), which forward sends back.
TEST(WarpMap, AFoldedScreenTriangleGivesOneOfThePreimages) {
  WarpMesh warp;
  warp.source.resize(5, 2);
  warp.source << 0, 0, 1, 0, 1, 1, 0, 1, 2, 0;
  warp.screen = warp.source;
  warp.screen.row(4) << 0.5, 0.25;  // (1, 0), (2, 0), (1, 1) lands inside the square, folded
  warp.F.resize(3, 3);
  warp.F << 1, 4, 2, 0, 1, 2, 0, 2, 3;
  const WarpMap map(warp);
  const Eigen::Vector2d q(0.7, 0.3);  // in the folded triangle's screen and in triangle 1's
  EXPECT_EQ(map.screen_triangle(q), 0);
  const std::optional<Eigen::Vector2d> p = map.inverse(q);
  ASSERT_TRUE(p);
  EXPECT_GT(p->x(), 1);  // in the fold's source, not at q in the square's
  ASSERT_TRUE(map.forward(*p));
  EXPECT_LT((*map.forward(*p) - q).norm(), 1e-12);
}

TEST(WarpMap, RejectsBadInput) {
  WarpMesh warp;
  warp.source.resize(3, 2);
  warp.source << 0, 0, 1, 0, 0, 1;
  warp.screen = warp.source;
  warp.F.resize(1, 3);
  warp.F << 0, 1, 2;
  const WarpMap map(warp);
  const double nan = std::numeric_limits<double>::quiet_NaN(),
               inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(map.forward({nan, 0}), InvalidInput);
  EXPECT_THROW(map.inverse({0, inf}), InvalidInput);
  EXPECT_THROW(map.source_triangle({nan, nan}), InvalidInput);
  EXPECT_THROW(map.screen_triangle({-inf, 0}), InvalidInput);
  Eigen::MatrixX2d P(3, 2);
  P << 0.1, 0.1, nan, 0.2, 0.3, 0.3;
  EXPECT_THROW(map.forward_batch(P), InvalidInput);
  EXPECT_THROW(map.inverse_batch(P), InvalidInput);
  try {
    map.forward_batch(P);
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("WarpMap::forward_batch: points row 1"), std::string::npos)
        << e.what();
  }

  WarpMesh bad = warp;
  bad.F(0, 2) = 3;
  EXPECT_THROW(WarpMap{bad}, InvalidInput);
  bad = warp;
  bad.F(0, 0) = -1;
  EXPECT_THROW(WarpMap{bad}, InvalidInput);
  bad = warp;
  bad.screen.conservativeResize(2, 2);
  EXPECT_THROW(WarpMap{bad}, InvalidInput);
  bad = warp;
  bad.source(1, 0) = nan;
  EXPECT_THROW(WarpMap{bad}, InvalidInput);
  bad = warp;
  bad.screen(2, 1) = inf;
  EXPECT_THROW(WarpMap{bad}, InvalidInput);
  bad = warp;
  bad.F.resize(0, 3);
  EXPECT_THROW(WarpMap{bad}, InvalidInput);
}

// The map keeps its own copy: it outlives and ignores later changes to the mesh it was built
// from, and its copies share it.
TEST(WarpMap, KeepsItsOwnCopyOfTheMesh) {
  auto warp = std::make_unique<WarpMesh>();
  warp->source.resize(3, 2);
  warp->source << 0, 0, 4, 0, 0, 4;
  warp->screen = 2 * warp->source;
  warp->F.resize(1, 3);
  warp->F << 0, 1, 2;
  const WarpMap map(*warp);
  warp->screen.setZero();
  warp.reset();
  const WarpMap copy = map;
  ASSERT_TRUE(copy.forward({1, 1}));
  EXPECT_LT((*copy.forward({1, 1}) - Eigen::Vector2d(2, 2)).norm(), 1e-12);
  EXPECT_EQ(&copy.mesh(), &map.mesh());
  EXPECT_EQ(map.mesh().screen(1, 0), 8);
}

}  // namespace
}  // namespace geolens
