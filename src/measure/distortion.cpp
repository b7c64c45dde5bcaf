#include "geolens/measure/distortion.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "numerics/svd2.h"

namespace geolens {

namespace {

Eigen::Matrix2d edges(const Eigen::MatrixX2d& P, const Eigen::MatrixX3i& F, Eigen::Index f) {
  Eigen::Matrix2d E;
  E.col(0) = (P.row(F(f, 1)) - P.row(F(f, 0))).transpose();
  E.col(1) = (P.row(F(f, 2)) - P.row(F(f, 0))).transpose();
  return E;
}

struct Measure {
  double magnification, conformal, source_area;
  bool flipped;
};

// The measures of triangle f (see measure_triangles).
Measure measure(const WarpMesh& mesh, Eigen::Index f) {
  const Eigen::Matrix2d S = edges(mesh.source, mesh.F, f);
  const double det_s = S.determinant();
  if (std::abs(det_s) <= 1e-12)
    return {0.0, std::numeric_limits<double>::infinity(), 0.5 * std::abs(det_s), true};
  const Eigen::Matrix2d J = edges(mesh.screen, mesh.F, f) * S.inverse();
  const SignedSvd2 svd = signed_svd(J);
  const double s1 = svd.s1, s2 = std::abs(svd.s2);
  return {std::sqrt(s1 * s2), s2 > 0 ? s1 / s2 - 1 : std::numeric_limits<double>::infinity(),
          0.5 * std::abs(det_s), J.determinant() <= 0};
}

}  // namespace

TriangleDistortion measure_triangles(const WarpMesh& mesh) {
  require(mesh.source.rows() == mesh.screen.rows(), "measure_triangles",
          "source and screen must have the same number of vertices");
  const Eigen::Index m = mesh.F.rows();
  TriangleDistortion d;
  d.magnification.resize(m);
  d.conformal.resize(m);
  d.source_area.resize(m);
  d.flipped.resize(m);
  for (Eigen::Index f = 0; f < m; ++f) {
    const Measure t = measure(mesh, f);
    d.magnification(f) = t.magnification;
    d.conformal(f) = t.conformal;
    d.source_area(f) = t.source_area;
    d.flipped(f) = t.flipped;
  }
  return d;
}

namespace {

// Triangles with a source centroid within `radius` of `point`, or else the one containing it.
std::vector<Eigen::Index> triangles_near(const WarpMesh& mesh, const Eigen::Vector2d& point,
                                         double radius) {
  std::vector<Eigen::Index> near;
  Eigen::Index containing = -1;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector2d a = mesh.source.row(mesh.F(f, 0)), b = mesh.source.row(mesh.F(f, 1)),
                          c = mesh.source.row(mesh.F(f, 2));
    if (((a + b + c) / 3.0 - point).norm() <= radius) near.push_back(f);
    auto side = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
      const Eigen::Vector2d e = q - p, r = point - p;
      return e.x() * r.y() - e.y() * r.x();
    };
    const double s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
    if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) containing = f;
  }
  if (near.empty() && containing >= 0) near.push_back(containing);
  require(!near.empty(), "magnification_at", "the point is outside the mesh");
  return near;
}

}  // namespace

double magnification_at(const WarpMesh& mesh, const TriangleDistortion& measures,
                        const Eigen::Vector2d& point, double radius) {
  double sum = 0, weight = 0;
  for (Eigen::Index f : triangles_near(mesh, point, radius)) {
    sum += measures.magnification(f) * measures.source_area(f);
    weight += measures.source_area(f);
  }
  return weight > 0 ? sum / weight : 0.0;
}

double magnification_at(const WarpMesh& mesh, const Eigen::Vector2d& point, double radius) {
  require(mesh.source.rows() == mesh.screen.rows(), "magnification_at",
          "source and screen must have the same number of vertices");
  double sum = 0, weight = 0;
  for (Eigen::Index f : triangles_near(mesh, point, radius)) {
    const Measure t = measure(mesh, f);
    sum += t.magnification * t.source_area;
    weight += t.source_area;
  }
  return weight > 0 ? sum / weight : 0.0;
}

double zoom_measure_radius(double region_size, double solved_side, int mesh) {
  require(mesh >= 2, "zoom_measure_radius", "mesh must be >= 2, got " + std::to_string(mesh));
  return std::max(solved_side / (mesh - 1), 0.05 * region_size);
}

DistortionSummary summarize(const TriangleDistortion& measures) {
  DistortionSummary s;
  double weight = 0;
  for (Eigen::Index f = 0; f < measures.conformal.size(); ++f) {
    if (measures.flipped(f)) ++s.flipped;
    if (!std::isfinite(measures.conformal(f))) continue;
    s.conformal_mean += measures.conformal(f) * measures.source_area(f);
    weight += measures.source_area(f);
    s.conformal_max = std::max(s.conformal_max, measures.conformal(f));
  }
  if (weight > 0) s.conformal_mean /= weight;
  return s;
}

}  // namespace geolens
