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

// One focus group's ring: the power law about `centre` between the focus (radius `inner` from
// it) and the footprint's edge, which along each ray is `outer` from it or the image border if
// nearer.
struct Ring {
  Eigen::Vector2d centre;
  double inner, outer, log_zoom;

  Ring(const FocusGroup& group, const std::vector<Lens>& lenses, double cell, double width,
       double height)
      : log_zoom(group.log_zoom) {
    const double near = near_distance(cell);
    // A region over an image side is magnified about a point on that side, so the side stays.
    Eigen::AlignedBox2d b;
    for (size_t k : group.lenses) b.extend(lenses[k].region.bounds());
    centre = group.centre;
    if (b.min().x() <= 0) centre.x() = 0;
    if (b.max().x() >= width) centre.x() = width;
    if (b.min().y() <= 0) centre.y() = 0;
    if (b.max().y() >= height) centre.y() = height;
    inner = group.reach + (centre - group.centre).norm() + near;
    outer = group.reach + group.margin - near;
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

std::vector<FocusGroup> focus_groups(const std::vector<Lens>& lenses,
                                     const std::vector<double>& log_zooms) {
  require(log_zooms.size() == lenses.size(), "focus_groups", "one log zoom per lens expected");
  const size_t n = lenses.size();
  // Union-find over the pairs whose magnified foci (disks of zoom x reach) overlap.
  std::vector<size_t> root(n);
  for (size_t k = 0; k < n; ++k) root[k] = k;
  auto find = [&](size_t k) {
    while (root[k] != k) k = root[k] = root[root[k]];
    return k;
  };
  auto magnified = [&](size_t k) { return std::exp(log_zooms[k]) * lenses[k].region.reach(); };
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      if ((lenses[i].region.peak() - lenses[j].region.peak()).norm() < magnified(i) + magnified(j))
        root[find(i)] = find(j);
  std::vector<FocusGroup> groups;
  std::vector<int> index(n, -1);
  for (size_t k = 0; k < n; ++k) {
    int& g = index[find(k)];
    if (g < 0) {
      g = int(groups.size());
      groups.emplace_back();
    }
    groups[size_t(g)].lenses.push_back(k);
  }
  for (FocusGroup& g : groups) {
    Eigen::AlignedBox2d peaks;
    double ratio = 0;
    for (size_t k : g.lenses) {
      peaks.extend(lenses[k].region.peak());
      ratio = std::max(ratio, footprint_ratio(lenses[k]));
      g.log_zoom = std::max(g.log_zoom, log_zooms[k]);
    }
    g.centre = g.lenses.size() == 1 ? lenses[g.lenses[0]].region.peak() : peaks.center();
    for (size_t k : g.lenses)
      g.reach =
          std::max(g.reach, (lenses[k].region.peak() - g.centre).norm() + lenses[k].region.reach());
    g.margin = (ratio - 1) * g.reach;
  }
  // Footprints stop where they would meet a neighbour's: where the disks of radius reach +
  // margin of two groups overlap, both margins shrink by the same factor until the disks touch
  // (their foci do not overlap, so there is room), and no lens pushes another.
  for (size_t i = 0; i < groups.size(); ++i) {
    for (size_t j = i + 1; j < groups.size(); ++j) {
      FocusGroup &a = groups[i], &b = groups[j];
      const double room = (a.centre - b.centre).norm() - a.reach - b.reach;
      if (a.margin + b.margin <= room) continue;
      const double scale = std::max(room, 0.0) / (a.margin + b.margin);
      a.margin *= scale;
      b.margin *= scale;
    }
  }
  return groups;
}

double radial_distortion_bound(double zoom, double ratio) {
  require(std::isfinite(zoom) && zoom >= 1 && std::isfinite(ratio) && ratio > 1,
          "radial_distortion_bound",
          "need zoom >= 1 and ratio > 1, got " + std::to_string(zoom) + " and " +
              std::to_string(ratio));
  const double k = 1 - std::log(zoom) / std::log(ratio);
  return k > 0 ? 1 / k - 1 : std::numeric_limits<double>::infinity();
}

std::vector<double> fitting_zooms(const std::vector<Lens>& lenses, double cell, double width,
                                  double height) {
  std::vector<double> log_zooms;
  for (const Lens& lens : lenses) log_zooms.push_back(std::log(lens.zoom));
  std::vector<double> fits(lenses.size());
  for (const FocusGroup& group : focus_groups(lenses, log_zooms)) {
    const Ring ring(group, lenses, cell, width, height);
    double ratio = std::numeric_limits<double>::infinity();
    constexpr int kRays = 720;
    for (int k = 0; k < kRays; ++k) {
      const double a = 2 * std::numbers::pi * (k + 0.5) / kRays;
      const Eigen::Vector2d u(std::cos(a), std::sin(a));
      if (ray_exits(ring.centre, u, width, height).minCoeff() <= 0) continue;  // leaves at once
      // The ring needs a few cells of the mesh to bend without folding a triangle.
      ratio = std::min(ratio, (ring.edge(u, width, height) - 2 * cell) / ring.inner);
    }
    for (size_t k : group.lenses) fits[k] = ratio > 1 ? std::pow(ratio, kFitExponent) : 1.0;
  }
  return fits;
}

namespace {

// The distance from p to the nearest region of `group`, pixels.
double group_distance(const FocusGroup& group, const std::vector<Lens>& lenses,
                      const Eigen::Vector2d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (size_t k : group.lenses) d = std::min(d, lenses[k].region.distance(p));
  return d;
}

}  // namespace

FocusField focus_field(const Eigen::MatrixX2d& V, const std::vector<Lens>& lenses,
                       const std::vector<double>& log_zooms, double cell, double width,
                       double height, double slack) {
  require(log_zooms.size() == lenses.size(), "focus_field", "one log zoom per lens expected");
  require(std::isfinite(cell) && cell > 0 && std::isfinite(slack) && slack >= 1, "focus_field",
          "cell must be > 0 and slack >= 1");
  for (double z : log_zooms)
    require(std::isfinite(z) && z >= 0, "focus_field",
            "log zoom must be finite and >= 0, got " + std::to_string(z));
  const Eigen::Index n = V.rows();
  const double near = near_distance(cell);
  FocusField out;
  out.groups = focus_groups(lenses, log_zooms);
  std::vector<Ring> rings;
  for (const FocusGroup& g : out.groups) rings.emplace_back(g, lenses, cell, width, height);
  FocusConstraints& c = out.constraints;
  c.focus.assign(size_t(n), -1);
  c.pinned.assign(size_t(n), 1);
  c.anisotropy = Eigen::VectorXd::Ones(n);
  out.log_scale = Eigen::VectorXd::Zero(n);
  out.level = Eigen::VectorXd::Zero(n);
  parallel_for(size_t(n), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const Eigen::Vector2d p = V.row(Eigen::Index(i)).transpose();
      // The group whose footprint p is deepest in (distance over margin), and the nearest focus.
      double nearest = std::numeric_limits<double>::infinity(), deepest = nearest;
      int owner = -1, closest = -1;
      for (size_t g = 0; g < out.groups.size(); ++g) {
        const double d = group_distance(out.groups[g], lenses, p);
        if (d < nearest) nearest = d, closest = int(g);
        if (d / out.groups[g].margin < deepest) deepest = d / out.groups[g].margin, owner = int(g);
        if (d < out.groups[g].margin - near) c.pinned[i] = 0;
      }
      if (nearest <= near) {
        c.focus[i] = closest;
        out.log_scale(Eigen::Index(i)) = out.groups[size_t(closest)].log_zoom;
      }
      if (owner >= 0) {
        // The radial bound along this vertex's ray of its group, with the slack; a ray too short
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

namespace {

// Moves the rows of X (pixels) by `group`'s power-law ring (see focus_start) at `log_zoom`.
void apply_ring(Eigen::MatrixX2d& X, const std::vector<Lens>& lenses, const FocusGroup& group,
                double log_zoom, double cell, double width, double height) {
  if (log_zoom <= 0) return;
  const double near = near_distance(cell);
  const Ring ring(group, lenses, cell, width, height);
  parallel_for(size_t(X.rows()), [&](size_t begin, size_t end) {
    for (Eigen::Index i = Eigen::Index(begin); i < Eigen::Index(end); ++i) {
      const Eigen::Vector2d q = X.row(i).transpose();
      const Eigen::Vector2d u = q - ring.centre;
      if (u.norm() == 0) continue;
      const double edge = ring.edge(u.normalized(), width, height);
      const double s = ring.inner + std::max(group_distance(group, lenses, q) - near, 0.0);
      // On or beyond the footprint's edge (an image border point lies on its ray's edge).
      if (s >= edge * (1 - 1e-12)) continue;
      const double g = std::exp(log_zoom * std::log(edge / s) / std::log(edge / ring.inner));
      X.row(i) = (ring.centre + g * u).transpose();
    }
  });
}

bool folds(const Eigen::MatrixX2d& X, const Eigen::MatrixX3i& F) {
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d a = X.row(F(f, 1)) - X.row(F(f, 0)), b = X.row(F(f, 2)) - X.row(F(f, 0));
    if (!(a.x() * b.y() - a.y() * b.x() > 0)) return true;
  }
  return false;
}

}  // namespace

Eigen::MatrixX2d focus_start(const Eigen::MatrixX2d& V, const std::vector<Lens>& lenses,
                             const std::vector<FocusGroup>& groups, double cell, double width,
                             double height) {
  Eigen::MatrixX2d X = V;
  for (const FocusGroup& group : groups)
    apply_ring(X, lenses, group, group.log_zoom, cell, width, height);
  return X;
}

std::vector<double> unfolding_zooms(const PlanarMesh& mesh, const std::vector<Lens>& lenses,
                                    double cell, double width, double height) {
  std::vector<double> log_zooms, zooms(lenses.size(), 1.0);
  for (const Lens& lens : lenses) log_zooms.push_back(std::log(lens.zoom));
  for (const FocusGroup& group : focus_groups(lenses, log_zooms)) {
    // The footprints are disjoint, so each group is tried on its own.
    for (const double fraction : {1.0, 0.8, 0.6, 0.4, 0.2}) {
      Eigen::MatrixX2d X = mesh.V;
      apply_ring(X, lenses, group, fraction * group.log_zoom, cell, width, height);
      if (folds(X, mesh.F)) continue;
      for (size_t k : group.lenses) zooms[k] = std::exp(fraction * group.log_zoom);
      break;
    }
  }
  return zooms;
}

FlattenResult flatten_focus(Flattener& flattener, const Eigen::MatrixX2d& V,
                            const std::vector<Lens>& lenses, const std::vector<FocusGroup>& groups,
                            double cell, double width, double height) {
  const Eigen::MatrixX2d start = focus_start(V, lenses, groups, cell, width, height);
  if (!flattener.admissible(start)) return flattener.solve(V);
  flattener.admit_anisotropy(start);
  return flattener.solve(start);
}

}  // namespace geolens
