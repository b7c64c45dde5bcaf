#include "geolens/lens/classic_lens.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "geolens/core/errors.h"
#include "geolens/geometry/grid.h"
#include "geolens/measure/distortion.h"
#include "geometry/conforming_mesh.h"
#include "lens/zoom_match.h"

namespace geolens {

std::string to_string(ClassicLens lens) {
  switch (lens) {
    case ClassicLens::kZoomIn:
      return "zoom_in";
    case ClassicLens::kFisheye:
      return "fisheye";
    case ClassicLens::kFisheyeSmooth:
      return "fisheye_smooth";
    case ClassicLens::kBifocal:
      return "bifocal";
    case ClassicLens::kFlattopLinear:
      return "flattop_linear";
    case ClassicLens::kFlattopCosine:
      return "flattop_cosine";
    case ClassicLens::kPowerRing:
      return "power_ring";
  }
  return "zoom_in";
}

ClassicLens parse_classic_lens(const std::string& name) {
  std::string names;
  for (const ClassicLens kind : kClassicLenses) {
    if (to_string(kind) == name) return kind;
    names += (names.empty() ? "" : ", ") + to_string(kind);
  }
  throw InvalidInput("parse_classic_lens: unknown lens '" + name + "', expected one of " + names);
}

double classic_source_distance(ClassicLens lens, double u, double zoom, double a) {
  require(std::isfinite(u) && u >= 0, "classic_source_distance",
          "screen distance must be finite and >= 0, got " + std::to_string(u));
  require(std::isfinite(zoom) && zoom >= 1, "classic_source_distance",
          "zoom must be finite and >= 1, got " + std::to_string(zoom));
  if (u >= 1) return u;
  require(std::isfinite(a) && a > 0 && a < 1, "classic_source_distance",
          "focus fraction must be in (0, 1), got " + std::to_string(a));
  const double d = zoom - 1;
  switch (lens) {
    case ClassicLens::kZoomIn:
      return u / zoom;
    case ClassicLens::kFisheye:
      // Sarkar and Brown 1992: G(t) = (d + 1) t / (d t + 1); solving u = G(t) for t.
      return u / (1 + d * (1 - u));
    case ClassicLens::kFisheyeSmooth:
      // The gain 1 + d (1 - u)^2 is z at the centre and falls to 1 at the rim with slope 0, so
      // T'(1) = 1 (C1 with the identity outside). T is increasing for any decreasing gain M:
      // T' = (M - u M') / M^2 > 0.
      return u / (1 + d * (1 - u) * (1 - u));
    case ClassicLens::kBifocal:
      // Spence and Apperley 1982: uniform z inside a, one uniform compression from a to 1.
      if (u <= a) return u / zoom;
      return a / zoom + (u - a) * (1 - a / zoom) / (1 - a);
    case ClassicLens::kFlattopLinear: {
      // Pietriga and Appert 2008: the gain M is z on the flat top and drops linearly to 1.
      const double gain = u <= a ? zoom : 1 + d * (1 - u) / (1 - a);
      return u / gain;
    }
    case ClassicLens::kFlattopCosine: {
      // The same with a raised-cosine drop-off: M' = 0 at a and at 1.
      const double gain =
          u <= a ? zoom : 1 + d * 0.5 * (1 + std::cos(std::numbers::pi * (u - a) / (1 - a)));
      return u / gain;
    }
    case ClassicLens::kPowerRing: {
      // In log coordinates the ring is linear: ln u = k ln t between (ln(a / z), ln a) and (0, 0).
      if (u <= a) return u / zoom;
      const double k = std::log(1 / a) / std::log(zoom / a);
      return std::pow(u, 1 / k);
    }
  }
  return u;
}

namespace {

void validate_lenses(const std::vector<CircleLens>& lenses, double width, double height,
                     const char* function) {
  require(!lenses.empty(), function, "need at least one lens");
  for (size_t k = 0; k < lenses.size(); ++k) {
    const CircleLens& lens = lenses[k];
    validate(lens, function);
    require(lens.center.x() >= 0 && lens.center.y() >= 0 && lens.center.x() <= width &&
                lens.center.y() <= height,
            function, "lens " + std::to_string(k + 1) + " has its centre outside the image");
    for (size_t j = 0; j < k; ++j) {
      require((lens.center - lenses[j].center).norm() >= lens.radius + lenses[j].radius, function,
              "lenses " + std::to_string(j + 1) + " and " + std::to_string(k + 1) +
                  " overlap; the classic lenses need disjoint disks");
    }
  }
}

std::vector<Ring> lens_rings(const std::vector<CircleLens>& lenses) {
  std::vector<Ring> rings;
  for (const CircleLens& lens : lenses) {
    rings.push_back({lens.center, lens.focus_fraction * lens.radius});
    rings.push_back({lens.center, lens.radius});
  }
  return rings;
}

// Relative distance from a rim within which a vertex counts as on it (ring vertices are placed
// on the circle up to rounding).
constexpr double kOnRim = 1e-9;

// Evaluates the lens on the ringed screen mesh.
WarpMesh evaluate(ClassicLens kind, const PlanarMesh& mesh, const std::vector<CircleLens>& lenses,
                  double width, double height) {
  WarpMesh warp;
  warp.screen_width = int(std::lround(width));
  warp.screen_height = int(std::lround(height));
  const Eigen::Index n = mesh.V.rows();
  Eigen::MatrixX2d screen = mesh.V, source = mesh.V;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (const CircleLens& lens : lenses) {
      const Eigen::Vector2d offset = mesh.V.row(i).transpose() - lens.center;
      const double u = offset.norm() / lens.radius;
      if (u >= 1 - kOnRim || u == 0) continue;
      source.row(i) =
          (lens.center +
           offset * (classic_source_distance(kind, u, lens.zoom, lens.focus_fraction) / u))
              .transpose();
    }
  }
  Eigen::MatrixX3i F = mesh.F;
  if (kind == ClassicLens::kZoomIn) {
    // The inset's rim vertices get their own copies, showing the source at radius r / z.
    std::vector<int> copy(size_t(n), -1);
    std::vector<Eigen::Vector2d> screen_copies, source_copies;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      for (const CircleLens& lens : lenses) {
        double mean = 0;
        for (int k = 0; k < 3; ++k)
          mean += (mesh.V.row(mesh.F(f, k)).transpose() - lens.center).norm() / 3;
        if (mean >= lens.radius) continue;
        for (int k = 0; k < 3; ++k) {
          const int i = mesh.F(f, k);
          const Eigen::Vector2d offset = mesh.V.row(i).transpose() - lens.center;
          if (offset.norm() < lens.radius * (1 - kOnRim)) continue;
          if (copy[size_t(i)] < 0) {
            copy[size_t(i)] = int(n + Eigen::Index(screen_copies.size()));
            screen_copies.push_back(mesh.V.row(i).transpose());
            source_copies.push_back(lens.center + offset / lens.zoom);
          }
          F(f, k) = copy[size_t(i)];
        }
        break;  // lens disks are disjoint
      }
    }
    screen.conservativeResize(n + Eigen::Index(screen_copies.size()), 2);
    source.conservativeResize(screen.rows(), 2);
    for (size_t k = 0; k < screen_copies.size(); ++k) {
      screen.row(n + Eigen::Index(k)) = screen_copies[k].transpose();
      source.row(n + Eigen::Index(k)) = source_copies[k].transpose();
    }
  }
  warp.F = std::move(F);
  warp.screen = std::move(screen);
  warp.source = std::move(source);
  return warp;
}

}  // namespace

PlanarMesh ringed_grid(double width, double height, int vertices_long_side,
                       const std::vector<Ring>& rings) {
  for (const Ring& ring : rings)
    require(ring.center.allFinite() && std::isfinite(ring.radius) && ring.radius > 0, "ringed_grid",
            "ring centre must be finite and radius > 0");
  const Grid grid = make_grid(width, height, vertices_long_side);
  std::vector<MeshCurve> curves;
  for (const Ring& ring : rings) curves.push_back(circle_curve(ring.center, ring.radius));
  return conform_mesh(grid, curves, 0.2 * grid.cell);
}

WarpMesh classic_warp(ClassicLens kind, const std::vector<CircleLens>& lenses, double width,
                      double height, int vertices_long_side) {
  require_mesh_vertices(vertices_long_side, "classic_warp");
  validate_lenses(lenses, width, height, "classic_warp");
  return evaluate(kind, ringed_grid(width, height, vertices_long_side, lens_rings(lenses)), lenses,
                  width, height);
}

Magnification match_classic_lens(ClassicLens kind, const std::vector<CircleLens>& targets,
                                 const std::vector<double>& measure_radius, double width,
                                 double height, int vertices_long_side) {
  require_mesh_vertices(vertices_long_side, "match_classic_lens");
  validate_lenses(targets, width, height, "match_classic_lens");
  require(measure_radius.size() == targets.size(), "match_classic_lens",
          "need one measure radius per lens");
  for (double radius : measure_radius)
    require(std::isfinite(radius) && radius > 0, "match_classic_lens",
            "measure radius must be finite and > 0, got " + std::to_string(radius));
  // The rings do not depend on the zoom, so one mesh serves every build.
  const PlanarMesh mesh = ringed_grid(width, height, vertices_long_side, lens_rings(targets));
  // The parameter is log z: 0 is the identity, and log(measured) grows about one for one with it.
  std::vector<double> log_z, zooms;
  for (const CircleLens& target : targets) {
    log_z.push_back(std::log(target.zoom));
    zooms.push_back(target.zoom);
  }
  int builds = 0;
  return match_zooms<Magnification>(
      std::move(log_z), zooms, 0.005, 20,
      [&](const std::vector<double>& x, int) {
        std::vector<CircleLens> lenses = targets;
        Magnification m;
        for (size_t k = 0; k < lenses.size(); ++k) {
          lenses[k].zoom = std::exp(x[k]);
          m.zoom_parameter.push_back(lenses[k].zoom);
        }
        m.warp = evaluate(kind, mesh, lenses, width, height);
        const TriangleDistortion measures = measure_triangles(m.warp);
        for (size_t k = 0; k < lenses.size(); ++k)
          m.zoom_measured.push_back(
              magnification_at(m.warp, measures, targets[k].center, measure_radius[k]));
        return m;
      },
      [](const Magnification& m, size_t k) { return m.zoom_measured[k]; },
      // Below the root: a secant step through the point before (the identity at first).
      [](size_t, const ZoomProbe& p) {
        const double slope = std::clamp((p.f - p.f_before) / (p.x - p.x_before), 0.1, 10.0);
        return p.x - p.f / slope;
      },
      [](size_t) { return std::numeric_limits<double>::infinity(); }, builds);
}

}  // namespace geolens
