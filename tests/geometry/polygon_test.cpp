#include "geometry/polygon.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <tuple>
#include <utility>

#include "geolens/core/errors.h"
#include "support/polygon_reference.h"

namespace geolens {
namespace {

using Points = std::vector<Eigen::Vector2d>;

Points star(double angle) {
  Points p;
  for (int k = 0; k < 10; ++k) {
    const double a = angle + k * std::numbers::pi / 5, r = k % 2 ? 19.1 : 50;
    p.push_back(Eigen::Vector2d(60, 55) + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return p;
}

const Points kL{{0, 0}, {200, 0}, {200, 60}, {60, 60}, {60, 200}, {0, 200}};

std::string message_of(const Points& poly) {
  try {
    validate_polygon(poly, "caller");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(ValidatePolygon, AcceptsSimplePolygonsOfEitherOrientation) {
  for (const Points& poly : {Points{{0, 0}, {10, 0}, {0, 10}}, Points{{0, 0}, {0, 10}, {10, 0}}, kL,
                             Points(kL.rbegin(), kL.rend()), star(0.3)}) {
    EXPECT_NO_THROW(validate_polygon(poly));
  }
}

TEST(ValidatePolygon, RejectsEachDefectNamingTheCallerAndTheVertices) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    Points poly;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {{{0, 0}, {1, 0}}, "caller: a polygon needs at least 3 vertices, got 2"},
      {{{0, 0}, {10, 0}, {nan, 5}}, "caller: vertex 2 (nan, 5) is not finite"},
      {{{0, 0}, {inf, 0}, {5, 5}}, "caller: vertex 1 (inf, 0) is not finite"},
      {{{0, 0}, {10, 0}, {20, 0}}, "caller: the polygon has zero area"},
      {{{0, 0}, {10, 0}, {10, 0}, {0, 10}}, "caller: vertices 1 and 2 coincide at (10, 0)"},
      // Bow tie (of non-zero area): edges 0 and 2 cross.
      {{{0, 0}, {10, 10}, {10, 0}, {0, 12}},
       "caller: edge 0 (0, 0)-(10, 10) and edge 2 (10, 0)-(0, 12) intersect"},
      // A vertex touching a non-adjacent edge.
      {{{0, 0}, {10, 0}, {10, 10}, {5, 0}, {0, 10}},
       "caller: edge 0 (0, 0)-(10, 0) and edge 2 (10, 10)-(5, 0) intersect"},
      // Edge 1 folds back along edge 0.
      {{{0, 0}, {10, 0}, {5, 0}, {5, 5}},
       "caller: edge 0 (0, 0)-(10, 0) and edge 1 (10, 0)-(5, 0) intersect"},
      // The closing edge runs back over edge 0.
      {{{0, 0}, {10, 0}, {10, 10}, {15, 0}},
       "caller: edge 0 (0, 0)-(10, 0) and edge 3 (15, 0)-(0, 0) intersect"},
      // Two loops sharing a vertex.
      {{{0, 0}, {10, 0}, {5, 5}, {10, 10}, {0, 10}, {5, 5}},
       "caller: edge 1 (10, 0)-(5, 5) and edge 4 (0, 10)-(5, 5) intersect"},
  };
  for (const Case& c : cases) EXPECT_EQ(message_of(c.poly), c.expected);
  EXPECT_THROW(validate_polygon({{0, 0}, {1, 1}}), InvalidInput);
}

// The first pair of edges that meet, found through the grid of edge buckets, is the one a check
// of every pair finds (exact integer arithmetic, random polygons on a small lattice: crossings,
// touchings and collinear overlaps), and a 100 000-vertex zigzag is checked at all.
TEST(ValidatePolygon, FirstMeetingEdgesAreThoseEveryPairShows) {
  using Point = std::array<long long, 2>;
  auto orientation = [](const Point& a, const Point& b, const Point& c) {
    const long long v = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    return (v > 0) - (v < 0);
  };
  auto on = [](const Point& a, const Point& b, const Point& c) {  // c collinear with a-b
    return std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) &&
           std::min(a[1], b[1]) <= c[1] && c[1] <= std::max(a[1], b[1]);
  };
  std::mt19937 random(7);
  int checked = 0, crossing = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = 4 + int(random() % 9);
    std::vector<Point> p(static_cast<size_t>(n));
    for (Point& q : p) q = {(long long)(random() % 12), (long long)(random() % 12)};
    long long twice_area = 0;
    bool coincide = false;
    for (int i = 0; i < n; ++i) {
      const Point &a = p[size_t(i)], &b = p[size_t((i + 1) % n)];
      twice_area += a[0] * b[1] - a[1] * b[0];
      coincide = coincide || a == b;
    }
    if (coincide || twice_area == 0) continue;
    // Every pair, in order: edges i < j meet other than at a vertex consecutive ones share.
    int first = -1, second = -1;
    for (int i = 0; i < n && first < 0; ++i)
      for (int j = i + 1; j < n && first < 0; ++j) {
        const Point &a = p[size_t(i)], &b = p[size_t((i + 1) % n)];
        const Point &c = p[size_t(j)], &d = p[size_t((j + 1) % n)];
        bool meet;
        if (j == i + 1)
          meet = orientation(a, b, d) == 0 &&
                 (a[0] - b[0]) * (d[0] - b[0]) + (a[1] - b[1]) * (d[1] - b[1]) > 0;
        else if (i == 0 && j == n - 1)
          meet = orientation(a, b, c) == 0 &&
                 (b[0] - a[0]) * (c[0] - a[0]) + (b[1] - a[1]) * (c[1] - a[1]) > 0;
        else {
          const int o1 = orientation(c, d, a), o2 = orientation(c, d, b);
          const int o3 = orientation(a, b, c), o4 = orientation(a, b, d);
          meet = (o1 * o2 < 0 && o3 * o4 < 0) || (o1 == 0 && on(c, d, a)) ||
                 (o2 == 0 && on(c, d, b)) || (o3 == 0 && on(a, b, c)) || (o4 == 0 && on(a, b, d));
        }
        if (meet) std::tie(first, second) = std::pair(i, j);
      }
    std::vector<Eigen::Vector2d> polygon;
    for (const Point& q : p) polygon.emplace_back(double(q[0]), double(q[1]));
    ++checked;
    try {
      validate_polygon(polygon, "test");
      EXPECT_EQ(first, -1) << "trial " << trial;
    } catch (const InvalidInput& e) {
      ++crossing;
      const std::string what = e.what();
      EXPECT_EQ(what.find("edge " + std::to_string(first) + " ("), what.find("edge "))
          << "trial " << trial << ": " << what;
      EXPECT_NE(what.find(" and edge " + std::to_string(second) + " ("), std::string::npos)
          << "trial " << trial << ": " << what;
    }
  }
  EXPECT_GT(checked, 1000);
  EXPECT_GT(crossing, 300);
  EXPECT_LT(crossing, checked);

  // A zigzag of 100 000 vertices whose last tooth crosses the first.
  std::vector<Eigen::Vector2d> zigzag;
  for (int i = 0; i < 50000; ++i) zigzag.emplace_back(i, i % 2 ? 10.0 : 0.0);
  zigzag.emplace_back(49999, -20);
  zigzag.emplace_back(0.5, -20);
  zigzag.emplace_back(0.5, 5);
  EXPECT_THROW(validate_polygon(zigzag, "test"), InvalidInput);
}

class PolygonFile : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (std::filesystem::path(::testing::TempDir()) / name).string();
    std::ofstream(path) << text;
    return path;
  }
};

TEST_F(PolygonFile, ReadsPairsSkippingBlankLinesAndComments) {
  const std::string path =
      write("geolens_polygon_good.txt",
            "# a triangle\n\n10 20\n  30.5\t-4e1  # trailing comment\n\t\n1e2 0.25\r\n");
  EXPECT_EQ(read_polygon_file(path), (Points{{10, 20}, {30.5, -40}, {100, 0.25}}));
  EXPECT_TRUE(read_polygon_file(write("geolens_polygon_empty.txt", "# nothing\n")).empty());
}

// What users have: CSV-like lines ("x,y", "x, y", "x;y") and a closed ring's repeated first
// vertex (dropped, only at the end and only when equal to the first).
TEST_F(PolygonFile, ReadsCommaAndSemicolonPairsAndDropsAClosingVertex) {
  const std::string path = write("geolens_polygon_csv.txt", "10,20\n30.5, -4e1\n1e2;0.25\n10 20\n");
  EXPECT_EQ(read_polygon_file(path), (Points{{10, 20}, {30.5, -40}, {100, 0.25}}));
  const std::string open = write("geolens_polygon_open.txt", "0 0\n4 0\n0 0.5\n0 0.0001\n");
  EXPECT_EQ(read_polygon_file(open).size(), 4u);
}

TEST_F(PolygonFile, RejectsMalformedLinesNamingFileAndLine) {
  for (const std::string bad : {"1 2 3", "1", "a b", "1 nan", "1 inf", "1,2,3", "1 2x"}) {
    const std::string path = write("geolens_polygon_bad.txt", "0 0\n# fine\n" + bad + "\n5 5\n");
    try {
      read_polygon_file(path);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()), "read_polygon_file: " + path +
                                           ":3: expected two finite numbers \"x y\", got \"" + bad +
                                           "\"");
    }
  }
}

// A line of a binary or huge file is shown by its first 60 characters and its length.
TEST_F(PolygonFile, ALongBadLineIsShortenedInTheMessage) {
  const std::string path = write("geolens_polygon_long.txt", std::string(100000, 'z') + "\n");
  try {
    read_polygon_file(path);
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_LT(what.size(), 300u);
    EXPECT_NE(what.find("...(100000 characters)"), std::string::npos) << what;
  }
}

TEST_F(PolygonFile, RejectsMissingFilesAndDirectories) {
  const std::string missing = ::testing::TempDir() + "/geolens_no_such_polygon.txt";
  try {
    read_polygon_file(missing);
    ADD_FAILURE();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()), "read_polygon_file: cannot open '" + missing + "'");
  }
  EXPECT_THROW(read_polygon_file(::testing::TempDir()), InvalidInput);
}

// Every dropped point is within the tolerance of the simplified loop, corners are kept, and a
// loop of a million points is simplified without recursion (a spiral-free circle here: 96 kept).
TEST(SimplifyLoop, DropsOnlyPointsWithinTheToleranceAndKeepsCorners) {
  Points l;  // the L with 50 points on each side
  for (size_t k = 0; k < kL.size(); ++k)
    for (int j = 0; j < 50; ++j)
      l.push_back(kL[k] + (kL[(k + 1) % kL.size()] - kL[k]) * (j / 50.0) +
                  Eigen::Vector2d(0.01 * std::sin(j), 0.01 * std::cos(j)));
  const Points kept = simplify_loop(l, 0.1);
  EXPECT_EQ(kept.size(), kL.size());
  for (const Eigen::Vector2d& corner : kL) {
    double nearest = 1e9;
    for (const Eigen::Vector2d& p : kept) nearest = std::min(nearest, (p - corner).norm());
    EXPECT_LT(nearest, 0.02);
  }
  auto distance_to = [](const Points& loop, const Eigen::Vector2d& p) {
    double d = 1e9;
    for (size_t k = 0; k < loop.size(); ++k)
      d = std::min(d, segment_distance(p, loop[k], loop[(k + 1) % loop.size()]));
    return d;
  };
  for (const Eigen::Vector2d& p : l) EXPECT_LE(distance_to(kept, p), 0.1);
  Points circle;
  for (int k = 0; k < 1000000; ++k) {
    const double a = 2 * std::numbers::pi * k / 1000000;
    circle.emplace_back(150 * std::cos(a), 150 * std::sin(a));
  }
  const Points round = simplify_loop(circle, 0.1);
  EXPECT_GT(round.size(), 50u);
  EXPECT_LT(round.size(), 200u);
  for (int k = 0; k < 1000000; k += 997) EXPECT_LE(distance_to(round, circle[size_t(k)]), 0.1);
}

TEST(RasterizePolygon, MarksExactlyTheNodesInside) {
  for (const Points& poly : {kL, star(0.2)}) {
    const int width = 90, height = 85;
    const Eigen::Vector2d origin(-3.3, -2.9);
    const double cell = 2.5;
    const std::vector<uint8_t> inside = rasterize_polygon(poly, width, height, origin, cell);
    ASSERT_EQ(inside.size(), size_t(width) * height);
    for (int j = 0; j < height; ++j) {
      for (int i = 0; i < width; ++i) {
        const Eigen::Vector2d p = origin + cell * Eigen::Vector2d(i, j);
        if (testing::brute_boundary_distance(poly, p) < 1e-9)
          continue;  // on the boundary: either way
        EXPECT_EQ(inside[size_t(j) * width + i], testing::brute_inside(poly, p)) << i << " " << j;
      }
    }
  }
  EXPECT_THROW(rasterize_polygon(kL, 0, 5, {0, 0}, 1), InvalidInput);
  EXPECT_THROW(rasterize_polygon(kL, 5, 5, {0, 0}, 0), InvalidInput);
}

TEST(PolygonIndex, AgreesWithBruteForce) {
  std::mt19937 rng(7);
  for (const Points& poly : {kL, star(0.2), star(1.3)}) {
    const PolygonIndex index(poly, 3.0);
    std::uniform_real_distribution<double> coordinate(-20, 220);
    for (int k = 0; k < 4000; ++k) {
      const Eigen::Vector2d p(coordinate(rng), coordinate(rng));
      const double d = testing::brute_boundary_distance(poly, p);
      if (d > 1e-9) {
        EXPECT_EQ(index.contains(p), testing::brute_inside(poly, p)) << p.transpose();
      }
      EXPECT_NEAR(index.boundary_distance(p, 7.5), std::min(d, 7.5), 1e-9) << p.transpose();
      EXPECT_NEAR(index.boundary_distance(p, 300), std::min(d, 300.0), 1e-9) << p.transpose();
    }
    // On the boundary the distance is 0 (up to rounding of the sample point).
    for (size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
      for (double t : {0.0, 0.3, 0.5})
        EXPECT_NEAR(index.boundary_distance(a + t * (b - a), 5), 0, 1e-12);
    }
  }
  EXPECT_EQ(PolygonIndex(kL, 3.0).boundary_distance({500, 500}, 5), 5);
  EXPECT_FALSE(PolygonIndex(kL, 3.0).contains({50, 1e300}));
  EXPECT_THROW(PolygonIndex(kL, 0.0), InvalidInput);
}

}  // namespace
}  // namespace geolens
