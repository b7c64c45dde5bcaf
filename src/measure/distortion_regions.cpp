#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "geolens/core/errors.h"
#include "geolens/measure/distortion.h"
#include "numerics/svd2.h"

namespace geolens {

void validate(const CircleLens& lens, const char* function) {
  require(lens.center.allFinite(), function, "lens centre must be finite");
  require(std::isfinite(lens.radius) && lens.radius > 0, function,
          "lens radius must be finite and > 0, got " + std::to_string(lens.radius));
  require(std::isfinite(lens.zoom) && lens.zoom >= 1, function,
          "lens zoom must be finite and >= 1, got " + std::to_string(lens.zoom));
  require(std::isfinite(lens.focus_fraction) && lens.focus_fraction > 0 && lens.focus_fraction < 1,
          function, "focus fraction must be in (0, 1), got " + std::to_string(lens.focus_fraction));
}

double focus_radius(const CircleLens& lens) {
  return lens.focus_fraction * lens.radius / lens.zoom;
}

std::string to_string(Zone zone) {
  switch (zone) {
    case Zone::kFocus:
      return "focus";
    case Zone::kTransition:
      return "transition";
    case Zone::kContext:
      return "context";
  }
  return "context";
}

std::vector<TriangleZone> classify_triangles(const WarpMesh& mesh,
                                             const std::vector<CircleLens>& lenses) {
  require(!lenses.empty(), "classify_triangles", "need at least one lens");
  for (const CircleLens& lens : lenses) validate(lens, "classify_triangles");
  std::vector<TriangleZone> zones(size_t(mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < lenses.size(); ++k) {
      const CircleLens& lens = lenses[k];
      double distance = 0;
      for (int v = 0; v < 3; ++v)
        distance += (mesh.source.row(mesh.F(f, v)).transpose() - lens.center).norm() / 3;
      if (distance / lens.radius >= best) continue;
      best = distance / lens.radius;
      zones[size_t(f)] = {distance < focus_radius(lens) ? Zone::kFocus
                          : distance < lens.radius      ? Zone::kTransition
                                                        : Zone::kContext,
                          int(k)};
    }
  }
  return zones;
}

namespace {

// Accumulates one zone; finish() turns the sums into means.
struct ZoneAccumulator {
  ZoneStatistics s;
  double conformal_sum = 0, area_distortion_sum = 0;

  void add(double conformal, double magnification, double area, bool flipped) {
    if (flipped || !std::isfinite(conformal)) {
      ++s.flipped;
      return;
    }
    const double scale = magnification * magnification;
    s.magnification_min =
        s.triangles == 0 ? magnification : std::min(s.magnification_min, magnification);
    s.magnification_max = std::max(s.magnification_max, magnification);
    s.conformal_max = std::max(s.conformal_max, conformal);
    ++s.triangles;
    s.area += area;
    conformal_sum += conformal * area;
    area_distortion_sum += (std::max(scale, 1 / scale) - 1) * area;
  }

  ZoneStatistics finish() const {
    ZoneStatistics out = s;
    if (s.area > 0) {
      out.conformal_mean = conformal_sum / s.area;
      out.area_distortion_mean = area_distortion_sum / s.area;
    }
    return out;
  }
};

}  // namespace

RegionStatistics measure_regions(const WarpMesh& mesh, const TriangleDistortion& measures,
                                 const std::vector<CircleLens>& lenses, double source_width,
                                 double source_height) {
  require(measures.conformal.size() == mesh.F.rows(), "measure_regions",
          "measures must come from measure_triangles(mesh)");
  require(std::isfinite(source_width) && std::isfinite(source_height) && source_width > 0 &&
              source_height > 0,
          "measure_regions", "source size must be positive");
  const std::vector<TriangleZone> zones = classify_triangles(mesh, lenses);
  ZoneAccumulator focus, transition, context, overall;
  std::vector<ZoneAccumulator> focus_per_lens(lenses.size());
  double visible = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const double conformal = measures.conformal(f), magnification = measures.magnification(f),
                 area = measures.source_area(f);
    const bool flipped = measures.flipped(f);
    const TriangleZone& where = zones[size_t(f)];
    if (where.zone == Zone::kFocus)
      focus_per_lens[size_t(where.lens)].add(conformal, magnification, area, flipped);
    ZoneAccumulator& zone = where.zone == Zone::kFocus        ? focus
                            : where.zone == Zone::kTransition ? transition
                                                              : context;
    zone.add(conformal, magnification, area, flipped);
    overall.add(conformal, magnification, area, flipped);
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (int k = 0; k < 3; ++k) centroid += mesh.screen.row(mesh.F(f, k)).transpose() / 3;
    if (centroid.x() >= 0 && centroid.y() >= 0 && centroid.x() <= mesh.screen_width &&
        centroid.y() <= mesh.screen_height)
      visible += area;
  }
  RegionStatistics r;
  r.focus = focus.finish();
  r.transition = transition.finish();
  r.context = context.finish();
  r.overall = overall.finish();
  for (const ZoneAccumulator& lens : focus_per_lens) {
    if (lens.s.triangles > 0)
      r.focus_uniformity =
          std::max(r.focus_uniformity, lens.s.magnification_max / lens.s.magnification_min);
  }
  const double image_area = source_width * source_height;
  r.occluded_area = std::max(0.0, image_area - visible);
  r.occluded_percent = 100 * r.occluded_area / image_area;
  return r;
}

Eigen::VectorXd eq7_energy(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                           const Eigen::MatrixX2d& X) {
  require(V3.rows() == X.rows(), "eq7_energy",
          "V3 and X must have the same number of vertices, got " + std::to_string(V3.rows()) +
              " and " + std::to_string(X.rows()));
  require(F.size() == 0 || (F.minCoeff() >= 0 && F.maxCoeff() < V3.rows()), "eq7_energy",
          "triangle indices out of range");
  Eigen::VectorXd energy(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    // The standard triangle (paper Fig. 4): v0 at the origin, v1 on the x axis.
    const Eigen::Vector3d a = V3.row(F(f, 1)) - V3.row(F(f, 0)),
                          b = V3.row(F(f, 2)) - V3.row(F(f, 0));
    const double length = a.norm();
    const double twice_area = a.cross(b).norm();
    require(length > 0 && twice_area > 0, "eq7_energy",
            "triangle " + std::to_string(f) + " is degenerate in 3D");
    Eigen::Matrix2d S;
    S << length, a.dot(b) / length, 0, twice_area / length;
    Eigen::Matrix2d E;
    E.col(0) = (X.row(F(f, 1)) - X.row(F(f, 0))).transpose();
    E.col(1) = (X.row(F(f, 2)) - X.row(F(f, 0))).transpose();
    // Closest rotation R = Rot(phi) Rot(theta) of the signed SVD, so J - R has singular values
    // s1 - 1 and s2 - 1 (s2 < 0 for a flipped triangle).
    const SignedSvd2 svd = signed_svd(E * S.inverse());
    energy(f) = twice_area * ((svd.s1 - 1) * (svd.s1 - 1) + (svd.s2 - 1) * (svd.s2 - 1));
  }
  return energy;
}

}  // namespace geolens
