#include "geolens/focus_lens.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "geolens/errors.h"
#include "parallel.h"

namespace geolens {

namespace {

// A mesh vertex within sqrt(2) cells of a curve has a triangle crossing it: the focus (and the
// footprint's edge) as the mesh holds them are that much wider (narrower).
double near_distance(double cell) { return std::numbers::sqrt2 * cell; }

// Where the ray from c (in or on the image rectangle) along the unit vector u meets the lines of
// the image's vertical and of its horizontal sides, pixels (infinite if parallel to them).
Eigen::Vector2d ray_exits(const Eigen::Vector2d& c, const Eigen::Vector2d& u, double width,
                          double height) {
  const double inf = std::numeric_limits<double>::infinity();
  const double x = u.x() > 0 ? (width - c.x()) / u.x() : u.x() < 0 ? -c.x() / u.x() : inf;
  const double y = u.y() > 0 ? (height - c.y()) / u.y() : u.y() < 0 ? -c.y() / u.y() : inf;
  return Eigen::Vector2d(std::max(x, 0.0), std::max(y, 0.0));
}

// One lens's ring: the power law about `centre` between the focus (radius `inner` from it) and
// the footprint's edge, which along each ray is `outer` from it or the image border if nearer.
struct Ring {
  Eigen::Vector2d centre;
  double inner, outer, log_zoom;

  Ring(const Lens& lens, double log_zoom_, double cell, double width, double height)
      : log_zoom(log_zoom_) {
    const double near = near_distance(cell);
    // A region over an image side is magnified about a point on that side, so the side stays.
    const Eigen::AlignedBox2d b = lens.region.bounds();
    centre = lens.region.peak();
    if (b.min().x() <= 0) centre.x() = 0;
    if (b.max().x() >= width) centre.x() = width;
    if (b.min().y() <= 0) centre.y() = 0;
    if (b.max().y() >= height) centre.y() = height;
    inner = lens.region.reach() + (centre - lens.region.peak()).norm() + near;
    outer = lens.region.reach() + footprint_margin(lens) - near;
  }
  // The footprint's edge along the ray with unit direction u, from the centre: `outer`, or short
  // of the image border where that is nearer. A smooth minimum (the 4-norm of the reciprocals)
  // of the three, so the edge does not turn sharply at an image corner, where the ring would
  // shear the mesh's triangles until they fold.
  double edge(const Eigen::Vector2d& u, double width, double height) const {
    const Eigen::Vector2d exits = ray_exits(centre, u, width, height);
    auto quartic = [](double x) { return 1 / ((x * x) * (x * x)); };
    return 1 / std::sqrt(std::sqrt(quartic(outer) + quartic(exits.x()) + quartic(exits.y())));
  }
};

// The zoom at which the radial bound's distortion reaches 4 (k = 0.2) for an edge / inner ratio.
constexpr double kFitExponent = 0.8;

}  // namespace

double footprint_ratio(const Lens& lens) {
  return lens.footprint > 0 ? lens.footprint : 2 * lens.zoom;
}

double footprint_margin(const Lens& lens) {
  return (footprint_ratio(lens) - 1) * lens.region.reach();
}

double radial_distortion_bound(double zoom, double ratio) {
  require(std::isfinite(zoom) && zoom >= 1 && std::isfinite(ratio) && ratio > 1,
          "radial_distortion_bound",
          "need zoom >= 1 and ratio > 1, got " + std::to_string(zoom) + " and " +
              std::to_string(ratio));
  const double k = 1 - std::log(zoom) / std::log(ratio);
  return k > 0 ? 1 / k - 1 : std::numeric_limits<double>::infinity();
}

double fitting_zoom(const Lens& lens, double cell, double width, double height) {
  const Ring ring(lens, std::log(lens.zoom), cell, width, height);
  double ratio = std::numeric_limits<double>::infinity();
  constexpr int kRays = 720;
  for (int k = 0; k < kRays; ++k) {
    const double a = 2 * std::numbers::pi * (k + 0.5) / kRays;
    const Eigen::Vector2d u(std::cos(a), std::sin(a));
    if (ray_exits(ring.centre, u, width, height).minCoeff() <= 0) continue;  // leaves at once
    ratio = std::min(ratio, ring.edge(u, width, height) / ring.inner);
  }
  return ratio > 1 ? std::pow(ratio, kFitExponent) : 1.0;
}

FocusField focus_field(const Eigen::MatrixX2d& V, const std::vector<Lens>& lenses,
                       const std::vector<double>& log_zooms, double cell, double width,
                       double height, double slack) {
  require(log_zooms.size() == lenses.size(), "focus_field", "one log zoom per lens expected");
  require(std::isfinite(cell) && cell > 0 && std::isfinite(slack) && slack >= 1, "focus_field",
          "cell must be > 0 and slack >= 1");
  const Eigen::Index n = V.rows();
  const double near = near_distance(cell);
  std::vector<double> margin(lenses.size());
  std::vector<Ring> rings;
  for (size_t k = 0; k < lenses.size(); ++k) {
    require(std::isfinite(log_zooms[k]) && log_zooms[k] >= 0, "focus_field",
            "log zoom must be finite and >= 0, got " + std::to_string(log_zooms[k]));
    margin[k] = footprint_margin(lenses[k]);
    rings.emplace_back(lenses[k], log_zooms[k], cell, width, height);
  }
  FocusField out;
  FocusConstraints& c = out.constraints;
  c.focus.assign(size_t(n), -1);
  c.pinned.assign(size_t(n), 1);
  c.anisotropy = Eigen::VectorXd::Ones(n);
  out.log_scale = Eigen::VectorXd::Zero(n);
  out.level = Eigen::VectorXd::Zero(n);
  parallel_for(size_t(n), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const Eigen::Vector2d p = V.row(Eigen::Index(i)).transpose();
      // The lens whose footprint p is deepest in (distance over margin), and the nearest focus.
      double nearest = std::numeric_limits<double>::infinity(), deepest = nearest;
      int owner = -1, closest = -1;
      for (size_t k = 0; k < lenses.size(); ++k) {
        const double d = lenses[k].region.distance(p);
        if (d < nearest) nearest = d, closest = int(k);
        if (d / margin[k] < deepest) deepest = d / margin[k], owner = int(k);
        if (d < margin[k] - near) c.pinned[i] = 0;
      }
      if (nearest <= near) {
        c.focus[i] = closest;
        out.log_scale(Eigen::Index(i)) = log_zooms[size_t(closest)];
      }
      if (owner >= 0) {
        // The radial bound along this vertex's ray of its lens, with the slack; a ray too short
        // for the zoom has no radial solution: the bound then only keeps the context from
        // folding over itself (at most 20, a sliver).
        const Ring& ring = rings[size_t(owner)];
        const Eigen::Vector2d u = (p - ring.centre).normalized();
        const double ratio = std::max(ring.edge(u, width, height) / ring.inner, 1.0 + 1e-9);
        const double k_power = 1 - ring.log_zoom / std::log(ratio);
        c.anisotropy(Eigen::Index(i)) = std::min(slack / std::max(k_power, 1e-9), 20.0);
      }
      out.level(Eigen::Index(i)) = c.pinned[i] ? 0.0 : 1.0;
    }
  });
  return out;
}

Eigen::MatrixX2d focus_start(const Eigen::MatrixX2d& V, const std::vector<Lens>& lenses,
                             const std::vector<double>& log_zooms, double cell, double width,
                             double height) {
  require(log_zooms.size() == lenses.size(), "focus_start", "one log zoom per lens expected");
  const double near = near_distance(cell);
  Eigen::MatrixX2d X = V;
  for (size_t k = 0; k < lenses.size(); ++k) {
    if (log_zooms[k] <= 0) continue;
    const Region& region = lenses[k].region;
    const Ring ring(lenses[k], log_zooms[k], cell, width, height);
    parallel_for(size_t(V.rows()), [&](size_t begin, size_t end) {
      for (Eigen::Index i = Eigen::Index(begin); i < Eigen::Index(end); ++i) {
        const Eigen::Vector2d q = X.row(i).transpose();
        const Eigen::Vector2d u = q - ring.centre;
        if (u.norm() == 0) continue;
        const double edge = ring.edge(u.normalized(), width, height);
        const double s = ring.inner + std::max(region.distance(q) - near, 0.0);
        // On or beyond the footprint's edge (an image border point lies on its ray's edge).
        if (s >= edge * (1 - 1e-12)) continue;
        const double g = std::exp(ring.log_zoom * std::log(edge / s) / std::log(edge / ring.inner));
        X.row(i) = (ring.centre + g * u).transpose();
      }
    });
  }
  return X;
}

FlattenResult flatten_focus(const Flattener& flattener, const Eigen::MatrixX2d& V,
                            const std::vector<Lens>& lenses, const std::vector<double>& log_zooms,
                            double cell, double width, double height) {
  const Eigen::MatrixX2d start = focus_start(V, lenses, log_zooms, cell, width, height);
  return flattener.admissible(start) ? flattener.solve(start) : flattener.solve(V);
}

}  // namespace geolens
