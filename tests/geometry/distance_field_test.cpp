#include "geometry/distance_field.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <tuple>

#include "geolens/core/errors.h"
#include "geometry/polygon.h"

namespace geolens {
namespace {

using Points = std::vector<Eigen::Vector2d>;
constexpr double kPi = std::numbers::pi;

DistanceTransform brute_force(const std::vector<uint8_t>& sites, int width, int height) {
  DistanceTransform out;
  out.squared.assign(sites.size(), std::numeric_limits<double>::infinity());
  out.nearest.assign(sites.size(), -1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int s = 0; s < width * height; ++s) {
        if (!sites[size_t(s)]) continue;
        const double d = std::pow(s % width - x, 2) + std::pow(s / width - y, 2);
        if (d < out.squared[size_t(y * width + x)]) {
          out.squared[size_t(y * width + x)] = d;
          out.nearest[size_t(y * width + x)] = s;
        }
      }
    }
  }
  return out;
}

class RandomSites : public ::testing::TestWithParam<std::tuple<int, int, double>> {};

TEST_P(RandomSites, DistanceIsExactAndTheFeatureIsANearestSite) {
  const auto [width, height, density] = GetParam();
  std::mt19937 rng(width * 1000 + height);
  std::bernoulli_distribution is_site(density);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<uint8_t> sites(size_t(width) * height);
    for (uint8_t& s : sites) s = is_site(rng);
    const DistanceTransform dt = distance_transform(sites, width, height);
    const DistanceTransform expected = brute_force(sites, width, height);
    for (size_t i = 0; i < sites.size(); ++i) {
      ASSERT_EQ(dt.squared[i], expected.squared[i]) << "node " << i;
      if (expected.nearest[i] < 0) {
        EXPECT_EQ(dt.nearest[i], -1);
        continue;
      }
      const int f = dt.nearest[i];
      ASSERT_GE(f, 0);
      EXPECT_TRUE(sites[size_t(f)]);
      const int x = int(i) % width, y = int(i) / width;
      EXPECT_EQ(std::pow(f % width - x, 2) + std::pow(f / width - y, 2), dt.squared[i]);
    }
  }
}

// Sparse sites leave whole rows and columns empty; density 0 leaves the raster empty.
INSTANTIATE_TEST_SUITE_P(Sizes, RandomSites,
                         ::testing::Values(std::make_tuple(1, 1, 0.5), std::make_tuple(17, 1, 0.2),
                                           std::make_tuple(1, 23, 0.2),
                                           std::make_tuple(31, 19, 0.01),
                                           std::make_tuple(24, 40, 0.1),
                                           std::make_tuple(40, 24, 0.5),
                                           std::make_tuple(13, 13, 0.0)));

TEST(DistanceTransform, RejectsMismatchedSizes) {
  EXPECT_THROW(distance_transform(std::vector<uint8_t>(10), 3, 3), InvalidInput);
  EXPECT_THROW(distance_transform({}, 0, 0), InvalidInput);
}

// The raster Region::polygon builds: nodes at cell centres, the box padded by 2 outside nodes.
struct Raster {
  int width = 0, height = 0;
  Eigen::Vector2d origin;
  double cell = 1;
  std::vector<uint8_t> inside;
  DistanceTransform outside;
  std::vector<uint8_t> axis;

  Raster(const Points& polygon, double cell_size) : cell(cell_size) {
    Eigen::Vector2d low = polygon[0], high = polygon[0];
    for (const Eigen::Vector2d& v : polygon) {
      low = low.cwiseMin(v);
      high = high.cwiseMax(v);
    }
    width = int(std::ceil((high.x() - low.x()) / cell)) + 4;
    height = int(std::ceil((high.y() - low.y()) / cell)) + 4;
    origin = low.array() - 1.5 * cell;
    inside = rasterize_polygon(polygon, width, height, origin, cell);
    std::vector<uint8_t> sites(inside.size());
    for (size_t i = 0; i < inside.size(); ++i) sites[i] = !inside[i];
    outside = distance_transform(sites, width, height);
    axis = medial_axis(inside, width, height, outside);
  }
  Eigen::Vector2d position(size_t i) const {
    return origin + cell * Eigen::Vector2d(double(i % size_t(width)), double(i / size_t(width)));
  }
};

Points rotated(Points points, const Eigen::Vector2d& centre, double angle) {
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(angle).toRotationMatrix();
  for (Eigen::Vector2d& p : points) p = centre + R * (p - centre);
  return points;
}

/// Samples of the polyline through `points`, at most `step` apart.
void sample(const Points& points, double step, Points* out) {
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const int n = int(std::ceil((points[i + 1] - points[i]).norm() / step));
    for (int k = 0; k <= n; ++k) out->push_back(points[i] + (points[i + 1] - points[i]) * k / n);
  }
}

double distance_to(const Points& samples, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& s : samples) best = std::min(best, (s - p).norm());
  return best;
}

/// A shape and its exact medial axis, as dense samples.
struct Shape {
  Points polygon;
  Points skeleton;
};

Shape rectangle() {  // 200 x 60: the centre line and the four corner bisectors
  Shape s{{{0, 0}, {200, 0}, {200, 60}, {0, 60}}, {}};
  for (const Points& branch : std::vector<Points>{
           {{0, 0}, {30, 30}, {170, 30}, {200, 0}}, {{0, 60}, {30, 30}}, {{200, 60}, {170, 30}}}) {
    sample(branch, 0.25, &s.skeleton);
  }
  return s;
}

Shape l_shape() {  // arms 60 wide; the reflex corner (60, 60) bends the axis along two parabolas
  Shape s{{{0, 0}, {200, 0}, {200, 60}, {60, 60}, {60, 200}, {0, 200}}, {}};
  const double j = 60 * std::sqrt(2.0) / (1 + std::sqrt(2.0));  // where the three branches meet
  Points parabola;  // equidistant from y = 0 and (60, 60)
  for (int k = 0; k <= 100; ++k) {
    const double x = j + (60 - j) * k / 100.0;
    parabola.emplace_back(x, (std::pow(x - 60, 2) + 3600) / 120);
  }
  Points mirrored;
  for (const Eigen::Vector2d& p : parabola) mirrored.emplace_back(p.y(), p.x());
  sample(parabola, 0.25, &s.skeleton);
  sample(mirrored, 0.25, &s.skeleton);
  for (const Points& branch : std::vector<Points>{{{0, 0}, {j, j}},
                                                  {{60, 30}, {170, 30}, {200, 0}},
                                                  {{170, 30}, {200, 60}},
                                                  {{30, 60}, {30, 170}, {0, 200}},
                                                  {{30, 170}, {60, 200}}}) {
    sample(branch, 0.25, &s.skeleton);
  }
  return s;
}

Shape star() {  // five points of radius 150 around (160, 160): five spokes to the tips
  Shape s;
  const Eigen::Vector2d centre(160, 160);
  for (int k = 0; k < 10; ++k) {
    const double angle = k * kPi / 5 - kPi / 2, radius = k % 2 ? 150 * 0.382 : 150;
    s.polygon.push_back(centre + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
    if (k % 2 == 0) sample({centre, s.polygon.back()}, 0.25, &s.skeleton);
  }
  return s;
}

class Skeleton : public ::testing::TestWithParam<std::tuple<int, double>> {};

// Every axis node lies on the exact medial axis (no spur), and the exact axis is covered
// wherever the shape is more than a few cells thick (near a corner tip the branch stops where
// the criterion can no longer tell the two sides from a digitisation step).
TEST_P(Skeleton, IsTheExactMedialAxisWithoutSpurs) {
  const auto [which, angle] = GetParam();
  const Shape shape = which == 0 ? rectangle() : which == 1 ? l_shape() : star();
  const Eigen::Vector2d centre = shape.polygon[0];
  const Points polygon = rotated(shape.polygon, centre, angle);
  const Points skeleton = rotated(shape.skeleton, centre, angle);
  const Raster r(polygon, 1.0);
  double worst = 0;
  int nodes = 0;
  for (size_t i = 0; i < r.axis.size(); ++i) {
    if (!r.axis[i]) continue;
    ++nodes;
    worst = std::max(worst, distance_to(skeleton, r.position(i)));
  }
  EXPECT_LE(worst, 1.25) << nodes << " axis nodes";
  const PolygonIndex index(polygon, 4);
  int covered = 0, checked = 0;
  for (const Eigen::Vector2d& s : skeleton) {
    if (index.boundary_distance(s, 6) < 6) continue;
    ++checked;
    bool near = false;
    for (size_t i = 0; i < r.axis.size() && !near; ++i) {
      near = r.axis[i] && (r.position(i) - s).norm() <= 1.5;
    }
    covered += near;
  }
  EXPECT_EQ(covered, checked);
}

INSTANTIATE_TEST_SUITE_P(RectangleLAndStar, Skeleton,
                         ::testing::Combine(::testing::Values(0, 1, 2),
                                            ::testing::Values(0.0, 0.13, 0.3, 0.7854, 1.1, 2.0)));

// The axis of a polygon approximating a circle is its centre: the 64 shallow corners (each
// subtending 5.6 degrees) grow no spoke.
TEST(MedialAxis, RegularPolygonWithManySidesHasOnlyItsCentre) {
  Points polygon;
  for (int k = 0; k < 64; ++k) {
    const double a = 0.05 + 2 * kPi * k / 64;
    polygon.push_back(Eigen::Vector2d(100, 100) + 100 * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  const Raster r(polygon, 1.0);
  int nodes = 0;
  for (size_t i = 0; i < r.axis.size(); ++i) {
    if (!r.axis[i]) continue;
    ++nodes;
    EXPECT_LE((r.position(i) - Eigen::Vector2d(100, 100)).norm(), 2.0);
  }
  EXPECT_GE(nodes, 1);
}

TEST(MedialAxis, SingleNodeIsItsOwnAxis) {
  std::vector<uint8_t> inside(9, 0), outside(9, 1);
  inside[4] = 1;
  outside[4] = 0;
  const std::vector<uint8_t> axis = medial_axis(inside, 3, 3, distance_transform(outside, 3, 3));
  EXPECT_EQ(axis, std::vector<uint8_t>({0, 0, 0, 0, 1, 0, 0, 0, 0}));
}

TEST(DepthRaster, DiscHasConicalDepthAndConstantThickness) {
  const int n = 121;
  const double cell = 0.5, radius = 25;
  const Eigen::Vector2d origin(10, 20), centre = origin + cell * Eigen::Vector2d(60, 60);
  std::vector<uint8_t> inside(size_t(n) * n);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      inside[size_t(y) * n + x] = (origin + cell * Eigen::Vector2d(x, y) - centre).norm() < radius;
    }
  }
  const DepthRaster r = depth_raster(inside, n, n, origin, cell);
  EXPECT_LE((r.peak - centre).norm(), cell);
  for (double d = 0; d < 1.2 * radius; d += 0.7) {
    const Eigen::Vector2d p = centre + d * Eigen::Vector2d(0.6, 0.8);
    const double a = r.axis_distance(p), b = r.boundary_distance(p);
    if (d < radius - cell) {
      EXPECT_NEAR(b, radius - d, cell) << d;
      EXPECT_NEAR(a, d, cell) << d;
      EXPECT_NEAR(a + b, radius, 1.5 * cell) << d;
      EXPECT_NEAR(depth_from_distances(a, b), 1 - d / radius, 1.5 * cell / radius) << d;
    } else if (d > radius + cell) {
      EXPECT_EQ(b, 0) << d;
      EXPECT_EQ(depth_from_distances(a, b), 0) << d;
    }
  }
  EXPECT_EQ(r.boundary_distance({-100, 0}), 0);
  EXPECT_EQ(r.axis_distance({-100, 0}), 0);
}

TEST(DepthRaster, PeakOfARectangleIsInTheMiddleOfItsCentreLine) {
  const int width = 64, height = 24;
  std::vector<uint8_t> inside(size_t(width) * height, 0);
  for (int y = 2; y < 22; ++y) {
    for (int x = 2; x < 62; ++x) inside[size_t(y) * width + x] = 1;
  }
  const DepthRaster r = depth_raster(inside, width, height, {0, 0}, 1.0);
  EXPECT_NEAR(r.peak.x(), 31.5, 1.0);
  EXPECT_NEAR(r.peak.y(), 11.5, 0.5);
}

TEST(DepthRaster, RejectsBadInput) {
  std::vector<uint8_t> inside(25, 0);
  EXPECT_THROW(depth_raster(inside, 5, 5, {0, 0}, 1.0), InvalidInput);  // nothing inside
  inside[12] = 1;
  EXPECT_NO_THROW(depth_raster(inside, 5, 5, {0, 0}, 1.0));
  EXPECT_THROW(depth_raster(inside, 5, 5, {0, 0}, 0.0), InvalidInput);
  EXPECT_THROW(depth_raster(inside, 5, 4, {0, 0}, 1.0), InvalidInput);
  inside[5] = 1;  // on the border
  EXPECT_THROW(depth_raster(inside, 5, 5, {0, 0}, 1.0), InvalidInput);
}

TEST(DepthFromDistances, IsZeroOnTheBoundaryOneOnTheAxis) {
  EXPECT_EQ(depth_from_distances(3, 0), 0);
  EXPECT_EQ(depth_from_distances(0, 0), 0);
  EXPECT_EQ(depth_from_distances(0, 2), 1);
  EXPECT_DOUBLE_EQ(depth_from_distances(1, 3), 0.75);
}

}  // namespace
}  // namespace geolens
