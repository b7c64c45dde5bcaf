#include "geolens/geometry/grid.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "geolens/core/errors.h"

namespace geolens {
namespace {

TEST(Grid, CoversTheImageWithPositiveTriangles) {
  const Grid g = make_grid(640, 480, 33);
  EXPECT_EQ(g.columns, 33);
  EXPECT_EQ(g.rows, 25);  // 480 / (640 / 32) + 1: square cells
  EXPECT_DOUBLE_EQ(g.V.col(0).maxCoeff(), 640);
  EXPECT_DOUBLE_EQ(g.V.col(1).maxCoeff(), 480);
  double area = 0;
  for (Eigen::Index f = 0; f < g.F.rows(); ++f) {
    const Eigen::Vector2d a = g.V.row(g.F(f, 0)), b = g.V.row(g.F(f, 1)), c = g.V.row(g.F(f, 2));
    const double cross = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    ASSERT_GT(cross, 0) << "triangle " << f;
    area += 0.5 * cross;
  }
  EXPECT_NEAR(area, 640.0 * 480.0, 1e-6);
}

TEST(Grid, SidesAndEdgesFormAManifoldDisk) {
  const Grid g = make_grid(100, 100, 11);
  int corners = 0, border = 0;
  for (uint8_t s : g.sides) {
    corners += (s == (kLeft | kTop)) + (s == (kRight | kTop)) + (s == (kLeft | kBottom)) +
               (s == (kRight | kBottom));
    border += s != 0;
  }
  EXPECT_EQ(corners, 4);
  EXPECT_EQ(border, 40);
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index f = 0; f < g.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int i = g.F(f, k), j = g.F(f, (k + 1) % 3);
      ++uses[{std::min(i, j), std::max(i, j)}];
    }
  int boundary_edges = 0;
  for (const auto& [edge, count] : uses) {
    ASSERT_LE(count, 2);
    if (count == 1) {
      ++boundary_edges;
      EXPECT_NE(g.sides[size_t(edge.first)] & g.sides[size_t(edge.second)], 0);
    }
  }
  EXPECT_EQ(boundary_edges, 40);
}

TEST(Grid, DiagonalsAlternate) {
  const Grid g = make_grid(30, 30, 4);
  // 4 columns: cell (0, 0) has corners 0, 1, 4, 5 and is split along 0-5 (down-right);
  // its neighbour (0, 1) has corners 1, 2, 5, 6 and is split along 2-5 (down-left).
  EXPECT_EQ(g.F.row(0), Eigen::RowVector3i(0, 1, 5));
  EXPECT_EQ(g.F.row(1), Eigen::RowVector3i(0, 5, 4));
  EXPECT_EQ(g.F.row(2), Eigen::RowVector3i(1, 2, 5));
  EXPECT_EQ(g.F.row(3), Eigen::RowVector3i(2, 6, 5));
}

TEST(Grid, RejectsBadSizes) {
  EXPECT_THROW(make_grid(0, 10, 10), InvalidInput);
  EXPECT_THROW(make_grid(10, -1, 10), InvalidInput);
  EXPECT_THROW(make_grid(10, 10, 1), InvalidInput);
}

}  // namespace
}  // namespace geolens
