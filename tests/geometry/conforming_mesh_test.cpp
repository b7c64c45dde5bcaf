#include "geometry/conforming_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geolens/core/errors.h"
#include "numerics/svd2.h"

namespace geolens {
namespace {

using Points = std::vector<Eigen::Vector2d>;

// An L (a reflex corner) and a thin spike (a 20 degree tip), pixels.
const Points kL = {{60, 60}, {120, 60}, {120, 180}, {240, 180}, {240, 240}, {60, 240}};
const Points kSpike = {{150, 40}, {270, 250}, {220, 250}};

double area2(const PlanarMesh& m, Eigen::Index f, const Eigen::MatrixX2d& X) {
  const Eigen::Vector2d a = X.row(m.F(f, 0)), b = X.row(m.F(f, 1)), c = X.row(m.F(f, 2));
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// Every triangle is counter-clockwise and not degenerate, and they cover the rectangle.
void expect_valid_cover(const PlanarMesh& m, double width, double height) {
  double area = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    ASSERT_GT(area2(m, f, m.V), 1e-6) << "triangle " << f;
    area += 0.5 * area2(m, f, m.V);
  }
  EXPECT_NEAR(area, width * height, 1e-6 * width * height);
  for (size_t i = 0; i < m.sides.size(); ++i) {
    const Eigen::Vector2d p = m.V.row(Eigen::Index(i));
    EXPECT_EQ(m.sides[i] != 0, p.x() == 0 || p.y() == 0 || p.x() == width || p.y() == height)
        << p.transpose();
  }
}

// No triangle has points on both sides of the curve: its three corners and seven points inside
// it are all on one side or on the curve, up to twice the sagitta of its longest edge on a curve of
// radius `radius` (0: a polygon, whose edges the mesh's follow exactly).
void expect_followed(const PlanarMesh& m, const MeshCurve& curve, double radius = 0) {
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector2d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const double longest = std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()});
    const double on = 1e-6 + (radius > 0 ? longest * longest / (4 * radius) : 0);
    int inside = 0, outside = 0;
    const std::vector<Eigen::Vector3d> weights = {{6, 0, 0}, {0, 6, 0}, {0, 0, 6}, {2, 2, 2},
                                                  {4, 1, 1}, {1, 4, 1}, {1, 1, 4}, {3, 3, 0},
                                                  {0, 3, 3}, {3, 0, 3}};  // sixths
    for (const Eigen::Vector3d& six : weights) {
      const Eigen::Vector3d w = six / 6;
      const double level = curve.level(w.x() * a + w.y() * b + w.z() * c);
      inside += level < -on;
      outside += level > on;
    }
    ASSERT_TRUE(inside == 0 || outside == 0) << "triangle " << f << ": " << a.transpose() << " | "
                                             << b.transpose() << " | " << c.transpose();
  }
}

TEST(ConformingMesh, FollowsAPolygonWithEveryCornerAVertex) {
  for (const Points& polygon : {kL, kSpike}) {
    const MeshCurve curve = polygon_curve(polygon);
    const Grid grid = make_grid(300, 300, 31);  // 10 px cells
    const PlanarMesh m = conform_mesh(grid, {curve}, 0.4 * grid.cell);
    expect_valid_cover(m, 300, 300);
    expect_followed(m, curve);
    for (const Eigen::Vector2d& corner : polygon) {
      double nearest = INFINITY;
      for (Eigen::Index i = 0; i < m.V.rows(); ++i)
        nearest = std::min(nearest, (Eigen::Vector2d(m.V.row(i)) - corner).norm());
      EXPECT_LT(nearest, 1e-9) << corner.transpose();
    }
  }
}

// At a polygon's corner no triangle spans more than 30 degrees (a wider one averages a map with
// a cone at the corner into a fold).
TEST(ConformingMesh, TrianglesAtACornerSpanAtMostThirtyDegrees) {
  const Grid grid = make_grid(300, 300, 31);
  const PlanarMesh m = conform_mesh(grid, {polygon_curve(kSpike)}, 0.4 * grid.cell);
  for (const Eigen::Vector2d& corner : kSpike) {
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
      for (int k = 0; k < 3; ++k) {
        if ((Eigen::Vector2d(m.V.row(m.F(f, k))) - corner).norm() > 1e-9) continue;
        const Eigen::Vector2d o = m.V.row(m.F(f, k));
        const Eigen::Vector2d u = Eigen::Vector2d(m.V.row(m.F(f, (k + 1) % 3))) - o,
                              v = Eigen::Vector2d(m.V.row(m.F(f, (k + 2) % 3))) - o;
        EXPECT_LE(std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v)), M_PI / 6 + 1e-9);
      }
    }
  }
}

TEST(ConformingMesh, FollowsCirclesTouchingEachOtherAndASide) {
  // Two circles that touch, one of them touching the mesh's side too.
  const std::vector<MeshCurve> curves = {circle_curve({100, 150}, 100),
                                         circle_curve({250, 150}, 50)};
  const Grid grid = make_grid(300, 300, 37);
  const PlanarMesh m = conform_mesh(grid, curves, 0.2 * grid.cell);
  expect_valid_cover(m, 300, 300);
  expect_followed(m, curves[0], 100);
  expect_followed(m, curves[1], 50);
}

// Refined where a map bends: the linear interpolation of the map over every triangle is within
// the tolerance at its edges' midpoints and its centroid, and the triangles stay well shaped.
TEST(ConformingMesh, RefinesWhereAMapBendsAndNowhereElse) {
  // A power-law ring about (150, 150): 1.5x within r = 60, the identity beyond r = 120, kinks
  // along both circles (which the mesh is made to follow) and curvature only between them.
  const Eigen::Vector2d c(150, 150);
  auto map = [c](const Eigen::MatrixX2d& P) {
    const double k = std::log(90.0 / 120) / std::log(60.0 / 120);
    Eigen::MatrixX2d X = P;
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const Eigen::Vector2d d = Eigen::Vector2d(P.row(i)) - c;
      const double r = d.norm();
      const double g = r < 60 ? 1.5 : r < 120 ? 120 * std::pow(r / 120, k) / r : 1;
      X.row(i) = (c + g * d).transpose();
    }
    return X;
  };
  MeshRefinement refine;
  refine.map = map;
  refine.tolerance = 0.1;
  const Grid grid = make_grid(300, 300, 31);
  const std::vector<MeshCurve> curves = {circle_curve(c, 60), circle_curve(c, 120)};
  const PlanarMesh coarse = conform_mesh(grid, curves, 0.4 * grid.cell);
  const PlanarMesh m = conform_mesh(grid, curves, 0.4 * grid.cell, refine);
  expect_valid_cover(m, 300, 300);
  expect_followed(m, curves[0], 60);
  expect_followed(m, curves[1], 120);
  EXPECT_GT(m.F.rows(), coarse.F.rows());
  const Eigen::MatrixX2d X = map(m.V);
  double worst = 0, thinnest = INFINITY;
  int beyond = 0;  // triangles split outside the ring, where the map is linear
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    Eigen::MatrixX2d P(4, 2);
    const Eigen::Vector2d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), d = m.V.row(m.F(f, 2));
    P << ((a + b) / 2).transpose(), ((b + d) / 2).transpose(), ((d + a) / 2).transpose(),
        ((a + b + d) / 3).transpose();
    const Eigen::MatrixX2d Y = map(P);
    const Eigen::RowVector2d xa = X.row(m.F(f, 0)), xb = X.row(m.F(f, 1)), xd = X.row(m.F(f, 2));
    worst = std::max({worst, (Y.row(0) - (xa + xb) / 2).norm(), (Y.row(1) - (xb + xd) / 2).norm(),
                      (Y.row(2) - (xd + xa) / 2).norm(), (Y.row(3) - (xa + xb + xd) / 3).norm()});
    const double longest = std::max({(a - b).norm(), (b - d).norm(), (d - a).norm()});
    thinnest = std::min(thinnest, area2(m, f, m.V) / (longest * longest));
    beyond += ((a + b + d) / 3 - c).norm() > 135 && longest < 0.99 * grid.cell;
  }
  EXPECT_LE(worst, refine.tolerance);
  EXPECT_GT(thinnest, 0.05);  // longest-edge bisection keeps the shapes (a grid triangle: 0.5)
  EXPECT_EQ(beyond, 0);
}

// Next to a curve, where following it leaves triangles with an obtuse corner, a triangle's
// linear map can be far off the slope of the map it samples (its shape distortion is then the
// mesh's, not the map's). With a slope tolerance, every triangle with a corner on a curve is
// split until its slope is within that fraction of its smaller singular value: measured here
// against the exact gradient of a quadratic map at the triangle's centroid (the estimate from
// the midpoints is an upper bound of that error for a quadratic).
TEST(ConformingMesh, SplitsTrianglesWhoseSlopeIsOffNextToACurve) {
  const Eigen::Vector2d c(150, 150);
  // p + ((p - c).x^2, (p - c).x (p - c).y) / 200: a bend that grows away from c.
  auto map = [c](const Eigen::MatrixX2d& P) {
    Eigen::MatrixX2d X = P;
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const Eigen::Vector2d d = Eigen::Vector2d(P.row(i)) - c;
      X.row(i) += Eigen::RowVector2d(d.x() * d.x(), d.x() * d.y()) / 200;
    }
    return X;
  };
  auto gradient = [c](const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = p - c;
    Eigen::Matrix2d J;
    J << 1 + d.x() / 100, 0, d.y() / 200, 1 + d.x() / 200;
    return J;
  };
  const Grid grid = make_grid(300, 300, 31);
  std::vector<MeshCurve> curves = {circle_curve(c, 57.3)};
  curves[0].slope = true;
  const double tolerance = 0.05;
  // The triangles with a corner on the curve whose slope is off by more than the tolerance.
  auto off = [&](double slope_tolerance, Eigen::Index* triangles) {
    MeshRefinement refine;
    refine.map = map;
    refine.tolerance = 1;  // positions alone split little
    refine.slope_tolerance = slope_tolerance;
    std::vector<int> on_curve;
    const PlanarMesh m = conform_mesh(grid, curves, 0.4 * grid.cell, refine, &on_curve);
    expect_valid_cover(m, 300, 300);
    expect_followed(m, curves[0], 57.3);
    *triangles = m.F.rows();
    const Eigen::MatrixX2d X = map(m.V);
    int count = 0;
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
      Eigen::Matrix2d source, mapped;
      for (int j = 0; j < 2; ++j) {
        source.col(j) = (m.V.row(m.F(f, j + 1)) - m.V.row(m.F(f, 0))).transpose();
        mapped.col(j) = (X.row(m.F(f, j + 1)) - X.row(m.F(f, 0))).transpose();
      }
      const Eigen::Matrix2d J = mapped * source.inverse();
      const Eigen::Vector2d centroid =
          (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))).transpose() / 3;
      const bool touches = on_curve[size_t(m.F(f, 0))] >= 0 || on_curve[size_t(m.F(f, 1))] >= 0 ||
                           on_curve[size_t(m.F(f, 2))] >= 0;
      const double error = signed_singular_values(J - gradient(centroid))(0);
      count += touches && error > tolerance * signed_singular_values(J)(1);
    }
    return count;
  };
  Eigen::Index plain = 0, split = 0;
  EXPECT_GT(off(0, &plain), 10);
  EXPECT_EQ(off(tolerance, &split), 0);
  EXPECT_GT(split, plain);
  EXPECT_LT(split, 2 * plain);  // only next to the curve
}

TEST(ConformingMesh, RefusesBadArguments) {
  const Grid grid = make_grid(100, 100, 11);
  EXPECT_THROW(conform_mesh(grid, {}, -1), InvalidInput);
  MeshRefinement refine;
  refine.map = [](const Eigen::MatrixX2d& P) { return P; };
  refine.tolerance = 0;
  EXPECT_THROW(conform_mesh(grid, {}, 1, refine), InvalidInput);
  refine.tolerance = 0.1;
  refine.slope_tolerance = -1;
  EXPECT_THROW(conform_mesh(grid, {}, 1, refine), InvalidInput);
  EXPECT_THROW(circle_curve({0, 0}, 0), InvalidInput);
  EXPECT_THROW(polygon_curve({{0, 0}, {1, 0}}), InvalidInput);
  EXPECT_THROW(conform_mesh(grid, {MeshCurve{}}, 1), InvalidInput);
}

}  // namespace
}  // namespace geolens
