#include "geolens/geometry/subdivide.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "geolens/core/errors.h"
#include "geolens/geometry/grid.h"

namespace geolens {
namespace {

// A steep gaussian-like bump of height 120 px and radius 60 px at (100, 100).
double bump(const Eigen::Vector2d& p) {
  const double d = (p - Eigen::Vector2d(100, 100)).norm();
  return d >= 60 ? 0.0 : 120.0 * std::exp(-d * d / (2 * 25.0 * 25.0));
}

double signed_area(const PlanarMesh& m, Eigen::Index f) {
  const Eigen::Vector2d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

TEST(Subdivide, RefinesOnlyWhereTheLiftStretchesAndStaysConforming) {
  const Grid grid = make_grid(300, 200, 31);
  SubdivisionOptions o;
  o.max_levels = 4;
  const PlanarMesh m = subdivide(grid, bump, o);
  ASSERT_GT(m.F.rows(), grid.F.rows());
  // The input's vertices keep their indices and positions.
  EXPECT_EQ(m.V.topRows(grid.V.rows()), grid.V);
  // Orientation kept, area kept, new vertices inside the bump's support.
  double area = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    ASSERT_GT(signed_area(m, f), 0) << "triangle " << f;
    area += signed_area(m, f);
  }
  EXPECT_NEAR(area, 300.0 * 200.0, 1e-6);
  for (Eigen::Index i = grid.V.rows(); i < m.V.rows(); ++i)
    EXPECT_LT((m.V.row(i) - Eigen::RowVector2d(100, 100)).norm(), 60 + 2 * grid.cell);
  // Every edge is used by one triangle (on the image border) or two (inside): no T-junctions.
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.F(f, k), b = m.F(f, (k + 1) % 3);
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  for (const auto& [edge, count] : uses) {
    const bool border = (m.sides[size_t(edge.first)] & m.sides[size_t(edge.second)]) != 0;
    EXPECT_EQ(count, border ? 1 : 2) << edge.first << "-" << edge.second;
  }
  // Euler characteristic of a disk: V - E + F = 1.
  EXPECT_EQ(m.V.rows() - Eigen::Index(uses.size()) + m.F.rows(), 1);
}

TEST(Subdivide, KeepsRightIsoscelesTriangles) {
  const Grid grid = make_grid(200, 200, 21);
  SubdivisionOptions o;
  o.max_levels = 3;
  const PlanarMesh m = subdivide(grid, bump, o);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    Eigen::Vector2d p[3];
    for (int k = 0; k < 3; ++k) p[k] = m.V.row(m.F(f, k));
    double largest_cos = -1;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d u = (p[(k + 1) % 3] - p[k]).normalized(),
                            v = (p[(k + 2) % 3] - p[k]).normalized();
      largest_cos = std::max(largest_cos, u.dot(v));
    }
    EXPECT_NEAR(largest_cos, std::sqrt(0.5), 1e-9);  // the two 45 degree corners
  }
}

TEST(Subdivide, FlatLiftAndZeroLevelsChangeNothing) {
  const Grid grid = make_grid(100, 100, 11);
  SubdivisionOptions o;
  const PlanarMesh flat = subdivide(
      grid, [](const Eigen::Vector2d&) { return 0.0; }, o);
  EXPECT_EQ(flat.F, grid.F);
  o.max_levels = 0;
  EXPECT_EQ(subdivide(grid, bump, o).F, grid.F);
}

TEST(Subdivide, RejectsBadOptions) {
  SubdivisionOptions o;
  o.max_stretch = 1.0;
  EXPECT_THROW(validate(o), InvalidInput);
  o = {};
  o.min_angle = 60;
  EXPECT_THROW(validate(o), InvalidInput);
  o = {};
  o.max_levels = -1;
  EXPECT_THROW(validate(o), InvalidInput);
}

}  // namespace
}  // namespace geolens
