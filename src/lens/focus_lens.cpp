#include "lens/focus_lens.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

#include "core/parallel.h"
#include "geolens/core/errors.h"
#include "geolens/lens/lens_options.h"
#include "lens/shared_room.h"
#include "numerics/bracketed_root.h"

namespace geolens {

namespace {

// Where the ray from c (in or on the image rectangle) along the unit vector u meets the lines of
// the image's vertical and of its horizontal sides, pixels (infinite if parallel to them).
Eigen::Vector2d ray_exits(const Eigen::Vector2d& c, const Eigen::Vector2d& u, double width,
                          double height) {
  const double inf = std::numeric_limits<double>::infinity();
  const double x = u.x() > 0 ? (width - c.x()) / u.x() : u.x() < 0 ? -c.x() / u.x() : inf;
  const double y = u.y() > 0 ? (height - c.y()) / u.y() : u.y() < 0 ? -c.y() / u.y() : inf;
  return Eigen::Vector2d(std::max(x, 0.0), std::max(y, 0.0));
}

// min(a, b) rounded where the two differ by less than an eighth of their sum (a quarter of their
// mean): C1, never above the minimum, and equal to it elsewhere (the quadratic smooth minimum,
// -w/4 - (a - b)^2 / 4w below the mean there). Its width is the sum's, symmetric in a and b: a
// width of the smaller put a crease where a = b (the partial derivatives jumped between 0.44
// and 0.5). Both partial derivatives lie in [0, 1] and sum to at most 1.
double smooth_min(double a, double b) {
  const double width = 0.125 * (a + b);
  // (also where either is infinite, a ray along a side, or not a number)
  if (!(std::abs(a - b) < width)) return std::min(a, b);
  const double h = (width - std::abs(a - b)) / width;
  return std::min(a, b) - 0.25 * h * h * width;
}

// The distance from p to the nearest region of `group`, pixels.
double group_distance(const FocusGroup& group, const std::vector<Lens>& lenses,
                      const Eigen::Vector2d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (size_t k : group.lenses) d = std::min(d, lenses[k].region.distance(p));
  return d;
}

// The distance outside a region as a ring reads it, pixels (0 inside), and the exact distance
// beside it. A circle's and a polygon's are computed here, a polygon's with the crease of the
// Euclidean distance along the bisector of each reflex corner (where its two edges are equally
// near) rounded by smooth_min: the ring's contours are offset curves of the focus, and there they
// would turn sharply, a crease in the picture that the refinement chased along the whole ray (the
// 5-pointed star at zoom 2.5: 8 passes, 37 k triangles). smooth_min's partial derivatives are
// non-negative and sum to at most 1, so the distance still grows by at most 1 per unit of length
// (no fold). Any other region's distance is its own.
class RingDistance {
 public:
  explicit RingDistance(const Region& region) : region_(region) {
    if (const std::optional<Circle> c = region.circle()) {
      circle_ = c;
      return;
    }
    const std::vector<Eigen::Vector2d> polygon =
        region.outline().value_or(std::vector<Eigen::Vector2d>{});
    const size_t n = polygon.size();
    double twice_area = 0;  // the shoelace formula: its sign is the orientation
    for (size_t k = 0, j = n - 1; k < n; j = k++)
      twice_area += polygon[j].x() * polygon[k].y() - polygon[k].x() * polygon[j].y();
    for (size_t k = 0; k < n; ++k) {
      const Eigen::Vector2d &a = polygon[(k + n - 1) % n], &b = polygon[k],
                            &c = polygon[(k + 1) % n];
      const double turn = (b - a).x() * (c - b).y() - (b - a).y() * (c - b).x();
      const double length2 = (c - b).squaredNorm();
      edges_.push_back({b, c - b, length2 > 0 ? 1 / length2 : 0.0, turn * twice_area < 0});
    }
  }

  // The distance from p, exact and rounded.
  struct Distance {
    double exact, rounded;
  };
  Distance operator()(const Eigen::Vector2d& p) const {
    if (circle_) {
      const double d = std::max((p - circle_->center).norm() - circle_->radius, 0.0);
      return {d, d};
    }
    if (edges_.empty()) {
      const double d = region_.distance(p);
      return {d, d};
    }
    // Inside by the crossing rule (PolygonIndex::contains); squared distances, and square roots
    // only where a reflex corner's two edges are within smooth_min's width of each other (the
    // farther below 9/7 of the nearer).
    bool inside = false;
    double nearest = std::numeric_limits<double>::infinity(), rounded = nearest;
    double first = 0, last = 0;
    auto corner = [&](double a, double b) {
      if (49 * std::max(a, b) < 81 * std::min(a, b))
        rounded = std::min(rounded, smooth_min(std::sqrt(a), std::sqrt(b)));
    };
    for (size_t k = 0; k < edges_.size(); ++k) {
      const Edge& e = edges_[k];
      const Eigen::Vector2d w = p - e.from;
      // The edge crosses p's horizontal line to p's right (the crossing rule's comparison,
      // multiplied through by the square of the edge's height).
      if ((w.y() < 0) != (w.y() < e.along.y()) &&
          (w.x() * e.along.y() - w.y() * e.along.x()) * e.along.y() < 0)
        inside = !inside;
      const double t = std::clamp(w.dot(e.along) * e.inverse_length2, 0.0, 1.0);
      const double d = (w - t * e.along).squaredNorm();
      nearest = std::min(nearest, d);
      if (k == 0) first = d;
      if (k > 0 && e.reflex) corner(last, d);
      last = d;
    }
    if (inside) return {0, 0};
    if (edges_[0].reflex) corner(last, first);
    const double exact = std::sqrt(nearest);
    return {exact, std::min(exact, rounded)};
  }

 private:
  struct Edge {
    Eigen::Vector2d from, along;  // edge k: from vertex k along to vertex k + 1
    double inverse_length2;
    bool reflex;  // the polygon turns against its orientation at vertex k
  };
  Region region_;
  std::optional<Circle> circle_;
  std::vector<Edge> edges_;
};

// The farthest t >= 0 where the ray c + t u (u a unit vector) meets the boundary of a region
// that is a circle or a polygon, pixels; 0 if it does not.
double farthest_crossing(const Region& region, const Eigen::Vector2d& c, const Eigen::Vector2d& u) {
  if (const std::optional<Circle> circle = region.circle()) {
    const Eigen::Vector2d w = circle->center - c;
    const double b = u.dot(w), d = b * b - w.squaredNorm() + circle->radius * circle->radius;
    return d >= 0 ? std::max(b + std::sqrt(d), 0.0) : 0.0;
  }
  double t = 0;
  const std::vector<Eigen::Vector2d> v = region.outline().value();
  for (size_t k = 0, j = v.size() - 1; k < v.size(); j = k++) {
    // c + t u = v[j] + s (v[k] - v[j]), s in [0, 1], by Cramer's rule.
    const Eigen::Vector2d e = v[k] - v[j], w = v[j] - c;
    const double det = u.x() * -e.y() + u.y() * e.x();
    if (det == 0) continue;  // parallel
    const double along = (w.x() * -e.y() + w.y() * e.x()) / det;
    const double s = (u.x() * w.y() - u.y() * w.x()) / det;
    if (s >= 0 && s <= 1) t = std::max(t, along);
  }
  return t;
}

// The direction of w as a fraction of a turn from the x axis towards y, in [0, 1): atan2 reduced
// to one octant and there a polynomial (Abramowitz and Stegun 4.4.49, |error| <= 2e-8 rad), four
// to five times faster than std::atan2, which the ring evaluates at every point it places.
double turns(const Eigen::Vector2d& w) {
  const double ax = std::abs(w.x()), ay = std::abs(w.y()), high = std::max(ax, ay);
  if (!(high > 0)) return 0;
  const double z = std::min(ax, ay) / high, z2 = z * z;
  // atan z = z (c0 + c1 z^2 + ... + c7 z^14) on [0, 1], by Horner's rule, scaled to be pi / 4
  // at z = 1 exactly: the octants then meet without a step (one of 2e-8 rad put a step of 7e-6
  // px into the footprint's edge, and the mesh that followed it made a triangle of area 0).
  constexpr std::array<double, 8> c = {0.9999993329, -0.3332985605, 0.1994653599, -0.1390853351,
                                       0.0964200441, -0.0559098861, 0.0218612288, -0.0040540580};
  constexpr double at_one = c[0] + c[1] + c[2] + c[3] + c[4] + c[5] + c[6] + c[7];
  double sum = 0;
  for (auto k = c.rbegin(); k != c.rend(); ++k) sum = sum * z2 + *k;
  double a = z * sum * (std::numbers::pi / 4 / at_one);
  if (ay > ax) a = std::numbers::pi / 2 - a;
  if (w.x() < 0) a = std::numbers::pi - a;
  if (w.y() < 0) a = 2 * std::numbers::pi - a;
  const double t = a / (2 * std::numbers::pi);
  return t < 1 ? t : 0.0;
}

// The zoom at which the radial bound's distortion reaches 4 (k = 0.2) for an edge / inner ratio.
constexpr double kFitExponent = 0.8;

// The zoom that fits where the footprint's edge is `ratio` times the focus's extent on the
// ray that has least room: a radial bound's distortion of 4.
double zoom_of_room(double ratio) { return ratio > 1 ? std::pow(ratio, kFitExponent) : 1.0; }

// (1 - e^-x) / x, 1 at x = 0: the ring's profile integrals below without their removable
// singularity.
double one_minus_exp_over(double x) {
  return std::abs(x) < 1e-12 ? 1 - 0.5 * x : -std::expm1(-x) / x;
}

// The ring's radial to tangential scale along a ray where the footprint's edge is e^lambda times
// the focus's extent, at log zoom L, with the magnified focus slid by `along` pixels along the
// ray (negative: back towards the centre) and the edge `edge` pixels from the centre: the power
// law's k = 1 - L / lambda, less along / (edge phi), phi = (1 - e^-(k lambda)) / k (see
// Ring::moved). It is constant along the ray.
double radial_ratio(double lambda, double log_zoom, double along, double edge) {
  const double x = lambda - log_zoom;  // k lambda
  const double k = lambda > 0 ? x / lambda : 1.0;
  if (along == 0) return k;
  return k - along / (edge * lambda * one_minus_exp_over(x));
}

// The rim's share of the distortion: the ring's profile may have up to 1 + kRimBudget times the
// power law's 1 / k (a distortion within 1.15 times the radial bound) to end without a crease.
constexpr double kRimBudget = 0.15;

// The ring's profile along a ray whose power law has L / lambda = a (k = 1 - a): ln g = L P(x)
// at x = ln(edge / s) / lambda, in [0, 1] from the footprint's edge to the focus, P(0) = 0,
// P(1) = 1. The power law is P = x, whose slope 1 to the end is the rim's crease (a radial scale
// of k inside the edge, 1 beyond). This P's slope rises linearly from 0 at the edge, m y with
// y = x / delta, over the rim 0 <= x <= delta and is m beyond, with m = (1 + b) / (1 + b a) and
// delta = 2 b (1 - a) / (1 + b), so that P(1) = 1: the ring's radial to tangential scale 1 - a P'
// is 1 at the edge (the warp is C1 there) and at least 1 - m a = (1 - a) / (1 + b a) within, a
// distortion of (1 + b a) / k - 1, within 1 + b times the power law's 1 / k - 1
// (rim_distortion_bound). A linear rise changes the radial scale by 2/3 of what a smoothstep's
// of the same width does at its steepest (the rim was a smoothstep with b = 0.3: 0.013-0.015 a
// pixel, 1.3 times the radial bound; now 0.010-0.016 a pixel, 1.15 times). b is kRimBudget up to
// a = 0.7 and falls to 0 at a = 0.85, where the rim is the power law's: near the fit's limit (a =
// 0.8, k = 0.2) the ring's compression next to a polygon's or a mask's tip then stays the power
// law's (a rim there folded a mask's tip on a fine mesh), and a ray a focus slides along may have
// a >= 1 (the slide gives it the room, Ring::moved), where a rim of slope 0 would fold.
struct Rim {
  // 0 up to z = 0, 1 from z = 1, the smoothstep 3 z^2 - 2 z^3 between: C1, so the rim's budget
  // fades with the slide without a kink. The shear changes quickly from ray to ray where a ray
  // grazes an image side (its edge there moves ~5 px per px across it), and a budget clamped
  // linearly put a crease along the ray where the fade began, which folded triangles of
  // 0.01 px^2 that the mesh's refinement made along it (a circle r 24 at zoom 3, 6 px below the
  // top of a 320 x 240 image, got 2.41 for "the mesh" at 11 places in 261 of a drag along the
  // side). The fade with a stays linear, as the rim's figures were measured (docs/design.md):
  // rounding its corners freed none of the places the sweeps still found held back.
  static double fade(double z) {
    z = std::clamp(z, 0.0, 1.0);
    return z * z * (3 - 2 * z);
  }
  double a, b, m, delta;
  // `shear`: a sliding focus's slide over the ray's room, |v| / (edge - zoom inner) (0 if none).
  explicit Rim(double a_, double shear = 0) : a(a_) {
    b = std::clamp(0.85 - a, 0.0, kRimBudget) * fade(1 - 2 * shear);
    m = (1 + b) / (1 + b * a);
    delta = 2 * b * (1 - a) / (1 + b);
  }
  // P(x).
  double profile(double x) const {
    if (x >= delta) return m * (x - 0.5 * delta);
    const double y = x / delta;
    return 0.5 * m * delta * y * y;
  }
  // The radial to tangential scale 1 - a P'(x) over the power law's 1 - a (1 where b = 0).
  double relative_radial(double x) const {
    if (b == 0) return 1;
    return (1 - a * m * std::min(x / delta, 1.0)) / (1 - a);
  }
  // (x - a P(x)) / (1 - a), 0 at the edge and 1 in the focus: the ring moves a point to g s =
  // edge e^(-(lambda - L) Q(x)) along its ray (for a circle), and a slide's weight (Ring::moved)
  // follows it.
  double spread(double x) const {
    if (x >= delta) return (x + b * a) / (1 + b * a);
    const double y = x / delta;
    return 2 * b * (y / (1 + b) - 0.5 * a * y * y / (1 + b * a));
  }
};

// One focus group's ring about `centre` (the group's, or a point on the image side its regions
// cross). Along the ray with unit direction u the focus reaches inner(u) from the centre (a
// smooth envelope of the farthest point within `near` of a region) and the footprint's edge
// lies at edge(u): the focus scaled by the footprint ratio, inside the group's disk, and short
// of the image border where that is nearer. Where the ring about the group's centre has too
// little room on the rays towards a side, the magnified focus slides away from it (least_slide).
struct Ring {
  static constexpr int kBins = 360;  // rays on which inner is found, interpolated between
  static constexpr int kRays = 720;  // rays on which the room is measured
  // The least ratio of the ring's radial to its tangential scale a fitting lens has on any ray:
  // a distortion of 4 (the radial bound's k at zoom = (edge / inner)^0.8).
  static constexpr double kLeastRadial = 1 - kFitExponent;
  Eigen::Vector2d centre, disk_centre;
  // The magnified focus's slide per unit of zoom - 1, pixels: the focus is magnified about
  // centre - pull (0 unless it slides).
  Eigen::Vector2d pull = Eigen::Vector2d::Zero();
  // The direction of the image side the ring's centre is on, along which alone it slides (0 if
  // it is on none).
  Eigen::Vector2d along = Eigen::Vector2d::Zero();
  double disk_radius, ratio, near, cell, width, height, margin = 0;
  // How far the centre, a side's point, is from the focus (beyond `near`), pixels: 0 for a ring
  // about the group's centre, or about a side's point in a region.
  double apart = 0;
  std::vector<double> inner_;          // per bin, or one value for a circle about its centre
  std::vector<RingDistance> regions_;  // the group's

  Ring(const FocusGroup& group, const std::vector<Lens>& lenses, double cell_, double band,
       double width_, double height_)
      : disk_centre(group.centre),
        disk_radius(group.reach + group.margin),
        ratio(1 + group.margin / group.reach),
        near(band),
        cell(cell_),
        width(width_),
        height(height_) {
    for (size_t k : group.lenses) regions_.emplace_back(lenses[k].region);
    place_at(group.fixed, group, lenses);
    // (A mesh that follows the regions resolves them: its band is a millionth of a cell.)
    for (size_t k : group.lenses)
      if (lenses[k].region.size() < 3 * cell && near > 0.5 * cell) margin = 2 * cell;
    if (group.on_side)
      along = centre.x() == 0 || centre.x() == width ? Eigen::Vector2d::UnitY()
                                                     : Eigen::Vector2d::UnitX();
    if (group.slides) slide_for(group.log_zoom);
  }

  // Makes the focus slide by the least slide at `log_zoom` (none at 0). About a side's point,
  // the point the focus is magnified about stays on the side, between its corners (beyond, a
  // ring short of room along the side folded the mesh; the ring about the corner is tried
  // there, magnify_near_side).
  void slide_for(double log_zoom) {
    pull = log_zoom > 0 ? Eigen::Vector2d(least_slide(log_zoom) / std::expm1(log_zoom))
                        : Eigen::Vector2d::Zero();
    if (along == Eigen::Vector2d::Zero()) return;
    const double at = centre.dot(along), length = along.x() > 0 ? width : height;
    pull = std::clamp(pull.dot(along), at - length, at) * along;
  }

  // The room on the ray along u: the focus's extent and the footprint's edge less `margin`, and
  // whether the ray stays in the image.
  struct Ray {
    double inner, edge;
    bool in_image;
  };
  Ray ray(const Eigen::Vector2d& u) const {
    const double inner_u = inner(u);
    return {inner_u, edge(u, inner_u) - margin, ray_exits(centre, u, width, height).minCoeff() > 0};
  }
  // The unit direction of ray k (a table made once: every ring measures its room on them, and
  // a choice near a side measures several rings per zoom tried).
  static const Eigen::Vector2d& ray_direction(int k) {
    static const std::array<Eigen::Vector2d, kRays> directions = [] {
      std::array<Eigen::Vector2d, kRays> d;
      for (int j = 0; j < kRays; ++j) {
        const double a = 2 * std::numbers::pi * (j + 0.5) / kRays;
        d[size_t(j)] = Eigen::Vector2d(std::cos(a), std::sin(a));
      }
      return d;
    }();
    return directions[size_t(k)];
  }

  // The least slide v of the magnified focus (pixels) at `log_zoom` with which the ring's
  // radial to tangential scale is at least kLeastRadial on every ray: v.u <= (k - kLeastRadial)
  // edge phi (radial_ratio). 0 where the ring about the centre has that room (the lens fits
  // unmoved); else the point nearest 0 of that intersection of half-planes, by Newton's method
  // on |v|^2 / 2 plus a stiff quadratic penalty on the violations (strictly convex, so the slide
  // is a continuous function of the lens's place, size and zoom). Where no slide gives the room
  // (a side on both sides), the penalty's minimum: min_ratio then tells the zoom that fits.
  Eigen::Vector2d least_slide(double log_zoom) const {
    // A circle's ring whose edge the border does not round (its disk 1.3 times clear of it, as
    // footprint_clear_of_border) has ratio all round: room without a slide where ratio^0.8 >= zoom.
    const double clear = 1.3 * disk_radius;
    if (inner_.size() == 1 && margin == 0 && centre.minCoeff() >= clear &&
        width - centre.x() >= clear && height - centre.y() >= clear &&
        kFitExponent * std::log(ratio) >= log_zoom)
      return Eigen::Vector2d::Zero();
    std::vector<std::pair<Eigen::Vector2d, double>> cuts;  // (u, the most v.u may be)
    bool needed = false;
    for (int k = 0; k < kRays; ++k) {
      const Eigen::Vector2d u = ray_direction(k);
      const Ray r = ray(u);
      if (!r.in_image || !(r.edge > 0)) continue;
      const double lambda = std::log(r.edge / r.inner), x = lambda - log_zoom;
      // (k - kLeastRadial) edge phi = edge ((1 - e^-x) - kLeastRadial lambda (1 - e^-x) / x),
      // a hair inside so the penalty's slight violation still has the room.
      const double most =
          r.edge * (-std::expm1(-x) - kLeastRadial * lambda * one_minus_exp_over(x)) -
          1e-6 * r.inner;
      // About a point of an image side, along the side only (its points stay on it).
      cuts.emplace_back(
          along == Eigen::Vector2d::Zero() ? u : Eigen::Vector2d(u.dot(along) * along), most);
      needed = needed || most < 0;
    }
    Eigen::Vector2d v = Eigen::Vector2d::Zero();
    if (!needed) return v;
    constexpr double kStiffness = 1e8;
    auto cost = [&](const Eigen::Vector2d& at) {
      double c = 0.5 * at.squaredNorm();
      for (const auto& [u, most] : cuts)
        c += 0.5 * kStiffness * std::pow(std::max(u.dot(at) - most, 0.0), 2);
      return c;
    };
    for (int iteration = 0; iteration < 100; ++iteration) {
      Eigen::Matrix2d hessian = Eigen::Matrix2d::Identity();
      Eigen::Vector2d gradient = v;
      for (const auto& [u, most] : cuts) {
        const double over = u.dot(v) - most;
        if (over <= 0) continue;
        hessian += kStiffness * u * u.transpose();
        gradient += kStiffness * over * u;
      }
      const Eigen::Vector2d step = hessian.ldlt().solve(gradient);
      double t = 1;
      const double before = cost(v);
      while (t > 1e-9 && cost(v - t * step) > before) t *= 0.5;
      v -= t * step;
      if (t * step.norm() < 1e-9 * (1 + v.norm())) break;
    }
    return v;
  }

  // The smallest ratio, over the rays into the image, of the footprint's edge, less `margin`,
  // to the focus's extent, and what bounds the edge on that ray. The margin is two cells for the
  // mesh to bend in when a region of the group spans fewer than three cells of a mesh that does
  // not follow it (below the mesh's resolution, where a ring folds or shrinks the focus), else 0:
  // a margin of cells made the zoom that fits depend on the mesh (a circle of radius 100 at 80 px
  // from a side fitted 1.92 at 100 x 100 and 2.0 at 400 x 400); a mesh too coarse for the ring
  // folds and is caught by unfolding_zooms.
  struct Room {
    double ratio = std::numeric_limits<double>::infinity();
    enum class By { kFootprint, kDisk, kSide } by = By::kFootprint;
    Eigen::Vector2d u = Eigen::Vector2d::UnitX();  // the ray
  };
  // Where the focus slides at log zoom L, a ray's ratio is the one whose radial bound has the
  // slid ring's radial to tangential scale there: e^(L / (1 - radial_ratio)).
  Room min_ratio(double log_zoom) const {
    Room room;
    const Eigen::Vector2d slide = std::expm1(log_zoom) * pull;
    for (int k = 0; k < kRays; ++k) {
      const Eigen::Vector2d u = ray_direction(k);
      const Ray ray_u = ray(u);
      if (!ray_u.in_image) continue;  // leaves at once
      double r = ray_u.edge / ray_u.inner;
      if (slide != Eigen::Vector2d::Zero() && r > 1 + 1e-9) {
        const double radial = radial_ratio(std::log(r), log_zoom, slide.dot(u), ray_u.edge);
        r = radial < 1 ? std::exp(log_zoom / (1 - radial))
                       : std::numeric_limits<double>::infinity();
      }
      if (!(r < room.ratio)) continue;
      room.ratio = r;
      room.u = u;
      const Eigen::Vector2d exits = ray_exits(centre, u, width, height);
      const double disk = disk_distance(u);
      room.by = exits.minCoeff() < std::min(ratio * ray_u.inner, disk) ? Room::By::kSide
                : disk < ratio * ray_u.inner                           ? Room::By::kDisk
                                                                       : Room::By::kFootprint;
    }
    return room;
  }

  // Puts the centre at c and finds the focus's extent along every ray from it.
  void place_at(const Eigen::Vector2d& c, const FocusGroup& group,
                const std::vector<Lens>& lenses) {
    centre = c;
    if (group.on_side) {
      apart = std::numeric_limits<double>::infinity();
      for (const RingDistance& region : regions_) apart = std::min(apart, region(centre).rounded);
      apart = std::max(apart - near, 0.0);
    }
    const double reach = group.reach + (centre - group.centre).norm() + near;
    if (group.lenses.size() == 1 && centre == group.centre &&
        lenses[group.lenses[0]].region.circle()) {
      inner_.assign(1, reach);
      return;
    }
    // Along each ray, from the reach inwards in half-cell steps to the first point within
    // `near` of a region, plus a step and `near` (the vertices of the focus between two rays).
    // Where the band is narrower than a step (a mesh that follows the regions), the crossing is
    // found to kCrossing px by bisection instead, or exactly where every region is a circle or a
    // polygon (the farthest point where the ray meets a boundary), and padded by the arc between
    // two rays there, so that the ring does not depend on the mesh; a band of sqrt 2 cells (a
    // mask, or a region smaller than the mesh resolves) is wider, and its focus depends on the
    // mesh anyway.
    constexpr double kCrossing = 1e-3;  // pixels
    const double step = 0.5 * cell;
    const bool refine = near < step;
    const bool exact =
        refine && std::all_of(group.lenses.begin(), group.lenses.end(), [&](size_t k) {
          return lenses[k].region.circle() || lenses[k].region.outline();
        });
    std::vector<double> found(kBins);
    for (int k = 0; k < kBins; ++k) {
      const double a = 2 * std::numbers::pi * k / kBins;
      const Eigen::Vector2d u(std::cos(a), std::sin(a));
      if (exact) {
        double t = 0;
        for (size_t j : group.lenses)
          t = std::max(t, farthest_crossing(lenses[j].region, centre, u));
        found[size_t(k)] = std::min(t * (1 + 2 * std::numbers::pi / kBins) + near, reach);
        continue;
      }
      auto away = [&](double t) { return group_distance(group, lenses, centre + t * u) > near; };
      // Where a step is farther than `near` by d, so are the steps within d of it (a distance
      // grows by at most 1 a unit of length): the walk skips them (it measured the distance at
      // every step, 90 % of a setup's time for small polygons and masks fitted beside a side).
      double t = reach;
      for (double d; t > 0 && (d = group_distance(group, lenses, centre + t * u)) > near;)
        t -= step * std::max(1.0, std::ceil((d - near) / step * (1 - 1e-9)));
      t = std::max(t, 0.0);
      if (!refine) {
        found[size_t(k)] = std::min(t + step + near, reach);
        continue;
      }
      if (t < reach && !away(t)) {
        double lo = t, hi = std::min(t + step, reach);  // away(hi) holds, away(lo) does not
        while (hi - lo > kCrossing) {
          const double mid = 0.5 * (lo + hi);
          (away(mid) ? hi : lo) = mid;
        }
        t = lo;
      }
      found[size_t(k)] = std::min(t * (1 + 2 * std::numbers::pi / kBins) + near, reach);
    }
    // A polygon's corner between two rays (a sharp tip the rays pass by) is as far as both.
    for (size_t k : group.lenses) {
      for (const Eigen::Vector2d& v :
           lenses[k].region.outline().value_or(std::vector<Eigen::Vector2d>{})) {
        const Eigen::Vector2d w = v - centre;
        const double a = turns(w) * kBins;
        const int below = std::min(int(a), kBins - 1);
        for (const int bin : {below, (below + 1) % kBins})
          found[size_t(bin)] = std::max(found[size_t(bin)], std::min(w.norm() + near, reach));
      }
    }
    // Its upper envelope of log-slope kSlope (per radian): no lower, and varying slowly enough
    // from ray to ray that the ring does not shear the mesh's triangles until they fold. That is
    // max over j of found[j] decay^(bins between k and j, round the circle): the running maximum,
    // decayed one bin a step, swept twice round each way (the kernel is exponential).
    constexpr double kSlope = 0.3;
    const double decay = std::exp(-kSlope * 2 * std::numbers::pi / kBins);
    inner_ = found;
    for (const int direction : {1, -1}) {
      double running = 0;
      for (int step = 0; step < 2 * kBins; ++step) {
        const size_t k = size_t(direction > 0 ? step % kBins : kBins - 1 - step % kBins);
        running = std::max(running * decay, found[k]);
        inner_[k] = std::max(inner_[k], running);
      }
    }
  }

  // Between two rays by Catmull-Rom's cubic (the tangent at a ray from its two neighbours): C1,
  // so the ring has no crease along every ray (linear interpolation put one of up to 8 % in
  // the start's slope along them). Within 0.1 % of the linear one between rays whose extents
  // differ by at most kSlope per radian, less than their padding by the arc between them.
  double inner(const Eigen::Vector2d& u) const {
    if (inner_.size() == 1) return inner_[0];
    const double a = turns(u) * kBins;
    const int k = std::min(int(a), kBins - 1);
    const double w = a - k;
    auto at = [&](int j) { return inner_[size_t((j + kBins) % kBins)]; };
    const double y1 = at(k), y2 = at(k + 1);
    const double m1 = 0.5 * (y2 - at(k - 1)), m2 = 0.5 * (at(k + 2) - y1);
    const double w2 = w * w, w3 = w2 * w;
    return (2 * w3 - 3 * w2 + 1) * y1 + (w3 - 2 * w2 + w) * m1 + (3 * w2 - 2 * w3) * y2 +
           (w3 - w2) * m2;
  }

  // The footprint's edge along u: the focus's extent scaled by the footprint ratio, within the
  // group's disk, or short of the image border where that is nearer. A smooth minimum of the
  // last three, so the edge does not turn sharply at an image corner, where the ring would shear
  // the mesh's triangles until they fold; it is the plain minimum where the farther is 9/7 of
  // the nearer or more, so the footprint of a circle clear of the border is the
  // group's disk, the circle its mesh follows (FocusPipeline::base_mesh).
  double edge(const Eigen::Vector2d& u) const { return edge(u, inner(u)); }
  // The same, given inner(u).
  double edge(const Eigen::Vector2d& u, double inner_u) const {
    const double outer = std::min(ratio * inner_u, disk_distance(u));
    const Eigen::Vector2d exits = ray_exits(centre, u, width, height);
    return smooth_min(outer, smooth_min(exits.x(), exits.y()));
  }

  // How far the ray along u meets the edge of the group's disk, pixels.
  double disk_distance(const Eigen::Vector2d& u) const {
    const Eigen::Vector2d w = centre - disk_centre;
    const double b = u.dot(w);
    return -b + std::sqrt(std::max(0.0, b * b - w.squaredNorm() + disk_radius * disk_radius));
  }

  // Where q lies on its ray: at t from the centre, at "radius" s >= t (s = inner where q is in the
  // focus, growing by at most 1 per unit of t), between inner and edge inside the ring.
  struct Place {
    Eigen::Vector2d u = Eigen::Vector2d::Zero();
    double t = 0, s = 0, inner = 0, edge = 0;
    double distance = 0;  // from q to the group's nearest region (exact), pixels
    bool in_footprint() const { return s < edge * (1 - 1e-12); }
  };
  Place place(const Eigen::Vector2d& q) const {
    Place p;
    p.t = (q - centre).norm();
    // The centre's ray points into the image, towards the group's centre (about a point of the
    // right side, the ray along x left the image at once: a vertex there stayed while its
    // neighbours moved with the focus, and the mesh folded).
    p.u = p.t > 0                 ? Eigen::Vector2d((q - centre) / p.t)
          : disk_centre != centre ? Eigen::Vector2d((disk_centre - centre).normalized())
                                  : Eigen::Vector2d(1, 0);
    p.inner = inner(p.u);
    p.edge = edge(p.u, p.inner);
    double rounded = std::numeric_limits<double>::infinity();
    p.distance = rounded;
    for (const RingDistance& region : regions_) {
      const RingDistance::Distance d = region(q);
      p.distance = std::min(p.distance, d.exact);
      rounded = std::min(rounded, d.rounded);
    }
    // A centre `apart` from the focus (a side's point off the regions) is in it for s: the
    // distance counts apart (1 - t / apart) less, so every ray begins at inner, and the slide,
    // which differs from ray to ray beyond the focus, is the focus's at the centre (it tore the
    // map there: a circle 20 px below the top side, magnified about the side's point, sliding).
    const double lead = apart > 0 ? apart * std::max(1 - p.t / apart, 0.0) : 0.0;
    p.s = std::max(p.t, p.inner + std::max(rounded - near - lead, 0.0));
    return p;
  }

  // Where the ring at `log_zoom` moves the point at `p` (in the footprint, not the centre):
  // centre + g t u, ln g = log_zoom P(ln(edge / s) / lambda), lambda = ln(edge / inner), P the
  // Rim's profile. s >= t and ds/dt <= 1 along the ray keep g t increasing (no fold) while edge
  // > zoom inner. A sliding focus adds w(s) v, v = (zoom - 1) pull, w = (1 - g s / edge) / (1 -
  // zoom inner / edge): 1 in the focus (magnified about centre - pull), 0 at the edge, and of the
  // same shape as g s, so the slide scales the ring's radial to tangential scale along the ray by
  // one factor, 1 - v.u / (edge - zoom inner) (radial_ratio; no fold while the slid focus ends
  // inside the edge).
  Eigen::Vector2d moved(const Place& p, double log_zoom) const {
    const double lambda = std::log(p.edge / p.inner), sigma = std::log(p.edge / p.s);
    const Rim rim = rim_on(p, lambda, log_zoom);
    const double x = sigma / lambda;
    const Eigen::Vector2d ringed = centre + std::exp(log_zoom * rim.profile(x)) * p.t * p.u;
    if (pull == Eigen::Vector2d::Zero()) return ringed;
    const double room = lambda - log_zoom, spread = rim.spread(x);
    const double w = spread * one_minus_exp_over(room * spread) / one_minus_exp_over(room);
    return ringed + w * std::expm1(log_zoom) * pull;
  }

  // Whether the ring moves p, in its footprint: not the centre, unless the focus slides.
  bool moves(const Place& p) const { return p.t > 0 || pull != Eigen::Vector2d::Zero(); }

  // The radial to tangential scale of the ring at `log_zoom` at p: the slid power law's along
  // the ray (radial_ratio) times the Rim's relative one.
  double radial(const Place& p, double log_zoom) const {
    const double lambda = std::log(std::max(p.edge / p.inner, 1 + 1e-9));
    const double k = radial_ratio(lambda, log_zoom, std::expm1(log_zoom) * pull.dot(p.u), p.edge);
    const double x = std::clamp(std::log(p.edge / p.s) / lambda, 0.0, 1.0);
    return k * rim_on(p, lambda, log_zoom).relative_radial(x);
  }

  // The Rim on p's ray, lambda = ln(edge / inner) there. A slide's weight has the ring's slope at
  // the edge, where the rim makes it 1 / k times the power law's: its shear across the ray, v
  // times that slope, would fold the mesh's triangles where the slide is large beside the room,
  // so the rim fades as the slide grows (none where |v| >= (edge - zoom inner) / 2).
  Rim rim_on(const Place& p, double lambda, double log_zoom) const {
    if (pull == Eigen::Vector2d::Zero()) return Rim(log_zoom / lambda);
    const double room = -p.edge * std::expm1(log_zoom - lambda);  // edge - zoom inner
    const double slide = std::expm1(log_zoom) * pull.norm();
    return Rim(log_zoom / lambda, room > 0 ? slide / room : 1.0);
  }

  // The footprint's edge is where s reaches edge along a ray: level = s - edge, negative inside,
  // grows along every ray, pixels (about the distance along the ray near the edge).
  double level(const Eigen::Vector2d& q) const {
    // The centre is in the focus (on an image corner, the ray of a point there, along rounding,
    // may leave the image at once).
    if ((q - centre).norm() <= 1e-9 * disk_radius) return -inner(Eigen::Vector2d(1, 0));
    const Place p = place(q);
    return p.s - p.edge;
  }

  // The point of the footprint's edge on q's ray (q not the centre), by a root of the level.
  Eigen::Vector2d onto_edge(const Eigen::Vector2d& q) const {
    const Eigen::Vector2d u = (q - centre).normalized();
    double hi = (q - centre).norm();  // level(0) < 0 <= level(hi), widened
    while (level(centre + hi * u) < 0) hi *= 2;
    auto along = [&](double t) { return level(centre + t * u); };
    return centre + bracketed_root(along, 0.0, hi, 1e-9) * u;
  }
};

// A group's warp: its ring, or where it blends two (FocusGroup::blend), the sum of their moves
// weighed. Each ring's Jacobian in its footprint is its radial and tangential scales along and
// across its ray (for a circle about its centre: symmetric and positive definite), 1 beyond, and
// in the focus the zoom, unrotated: the blend magnifies the focus by the zoom, and a weighed sum
// of symmetric positive definite matrices is one whose ratio of singular values is at most the
// largest of theirs (its extreme eigenvalues lie between the weighed sums of theirs), so the
// blend folds nothing and its distortion is at most its rings' (a slide's shear and a polygon's
// envelope make a Jacobian a little unsymmetric: the anisotropy's slack).
struct Warp {
  struct Part {
    Ring ring;
    double weight;     // the weights sum to 1
    double log_share;  // its log zoom less the group's
  };
  std::vector<Part> parts;
  // A lens's own ring, the ring about a side's point, and the corner's (magnify_near_side).
  static constexpr size_t kMostParts = 3;

  Warp(const FocusGroup& group, const std::vector<Lens>& lenses, double cell, double band,
       double width, double height) {
    add(group, 1, 0, lenses, cell, band, width, height);
  }
  void add(FocusGroup group, double weight, double log_share, const std::vector<Lens>& lenses,
           double cell, double band, double width, double height) {
    const double t = group.blend ? group.blend_weight : 0.0;
    const double own = std::log((1 - t * group.blend_zoom) / (1 - t));
    const std::shared_ptr<const FocusGroup> blend = std::move(group.blend);
    group.log_zoom += own;  // (its slide is found at its own zoom)
    require(parts.size() < kMostParts, "Warp", "a blend of more than three rings");
    parts.push_back(
        {Ring(group, lenses, cell, band, width, height), weight * (1 - t), log_share + own});
    if (blend)
      add(*blend, weight * t, log_share + std::log(group.blend_zoom), lenses, cell, band, width,
          height);
  }
  const Ring& ring() const { return parts.front().ring; }

  // Where q lies on every ring's ray.
  struct Place {
    std::array<Ring::Place, kMostParts> at;  // (a vector cost a heap block a vertex)
    double distance = 0;                     // from q to the group's nearest region (exact), pixels
    double depth = 1;  // the least s / edge over the rings whose footprint holds q, else 1
  };
  Place place(const Eigen::Vector2d& q) const {
    Place p;
    for (size_t i = 0; i < parts.size(); ++i) {
      p.at[i] = parts[i].ring.place(q);
      if (p.at[i].in_footprint()) p.depth = std::min(p.depth, p.at[i].s / p.at[i].edge);
    }
    p.distance = p.at[0].distance;
    return p;
  }
  // Whether a ring moves q.
  bool moves(const Place& p) const {
    for (size_t i = 0; i < parts.size(); ++i)
      if (p.at[i].in_footprint() && parts[i].ring.moves(p.at[i])) return true;
    return false;
  }
  // Where the warp at `log_zoom` moves q, at p.
  Eigen::Vector2d moved(const Eigen::Vector2d& q, const Place& p, double log_zoom) const {
    Eigen::Vector2d out = q;
    for (size_t i = 0; i < parts.size(); ++i)
      if (p.at[i].in_footprint() && parts[i].ring.moves(p.at[i]))
        out += parts[i].weight * (parts[i].ring.moved(p.at[i], log_zoom + parts[i].log_share) - q);
    return out;
  }
  // The largest distortion of its rings at q (the ratio of the radial to the tangential scale,
  // or its inverse where a slid ring stretches along the ray), 1 beyond every footprint.
  double distortion(const Place& p, double log_zoom) const {
    double most = 1;
    for (size_t i = 0; i < parts.size(); ++i) {
      if (!p.at[i].in_footprint()) continue;
      const double k = parts[i].ring.radial(p.at[i], log_zoom + parts[i].log_share);
      most = std::max(most, std::max(1 / std::max(k, 1e-9), k));
    }
    return most;
  }
  // The footprint is the union of the rings': its level is the least of theirs, and a point of
  // its edge near q the one of the ring whose level is least there.
  double level(const Eigen::Vector2d& q) const {
    double least = std::numeric_limits<double>::infinity();
    for (const Part& part : parts) least = std::min(least, part.ring.level(q));
    return least;
  }
  Eigen::Vector2d onto_edge(const Eigen::Vector2d& q) const {
    const Ring* least = &ring();
    double lowest = least->level(q);
    for (size_t i = 1; i < parts.size(); ++i)
      if (const double level = parts[i].ring.level(q); level < lowest)
        lowest = level, least = &parts[i].ring;
    return least->onto_edge(q);
  }
};

// The fractions of a log zoom tried, in order, when a ring folds the mesh or its start is not
// admissible.
constexpr std::array<double, 5> kZoomFractions = {1.0, 0.8, 0.6, 0.4, 0.2};

// The point a region with bounds `bounds` and centre `centre` near the sides of a width x height
// image is magnified about, less the centre (pixels), as focus_groups estimates it for the
// footprint: per side, the side's point nearest the centre, weighted by how much of the gap the
// unmoved ring needs at log zoom L is missing (1 - gap / (extent (zoom^1.25 - 1)), in [0, 1],
// the extent from the centre to the bounds' side; zoom^1.25 makes the radial bound's
// distortion 4): 0 far from every side, the side's point where the region touches or crosses
// it. Continuous in the lens's place and zoom.
Eigen::Vector2d estimated_fixed_offset(const Eigen::Vector2d& centre,
                                       const Eigen::AlignedBox2d& bounds, double log_zoom,
                                       double width, double height) {
  const double need = std::expm1(log_zoom / kFitExponent);
  auto towards = [&](double to_side, double extent) {
    if (!(need > 0 && extent > 0)) return to_side <= extent ? to_side : 0.0;
    return to_side * std::clamp(1 - (to_side - extent) / (extent * need), 0.0, 1.0);
  };
  const Eigen::Vector2d low = centre - bounds.min(), high = bounds.max() - centre;
  return Eigen::Vector2d(towards(width - centre.x(), high.x()) - towards(centre.x(), low.x()),
                         towards(height - centre.y(), high.y()) - towards(centre.y(), low.y()));
}

}  // namespace

double footprint_ratio(const Lens& lens) {
  return lens.footprint > 0 ? lens.footprint : 2 * lens.zoom;
}

namespace {

// Fractions of a lens's reach: within kSideSnap of a side it is magnified about the side's
// point; from kSideBand its ring about that point is held, and from kSideReach not tried
// (magnify_near_side). kSideRamp: the slide's hold grows by e^kSideRamp a reach.
constexpr double kSideSnap = 0.1, kSideBand = 0.5, kSideReach = 1.5, kSideRamp = 1;
// The ring about a side's point is blended in as a circle's slide off the side moves its
// magnified focus from kBlendFrom to kSideSlide of the way to where that ring would (the slide's
// thin gap folded the mesh beyond: r 22 at zoom 4.26, 7-9 px off the side), shifting towards
// the ring that fits more over kBlendLog in the logs of their shares of the zoom
// (magnify_near_side).
constexpr double kBlendFrom = 0.25, kSideSlide = 0.75, kBlendLog = 0.1;
// A slide that fits does so to within about a millionth (least_slide's penalty leaves its cuts a
// hair violated): it is taken to fit.
constexpr double kFitTolerance = 1e-6;

// The margin of the footprint of a focus of extent `reach` scaled by `ratio` about a point
// `offset` from its centre (pixels): (ratio - 1) (reach + |offset|), at most `most`.
double footprint_margin(double ratio, double reach, const Eigen::Vector2d& offset, double most) {
  return std::min(most, (ratio - 1) * (reach + offset.norm()));
}

// The zoom `ring` fits at log zoom L, over e^L (>= 1 where it fits).
double fit_over(const Ring& ring, double log_zoom) {
  return zoom_of_room(ring.min_ratio(log_zoom).ratio) / std::exp(log_zoom);
}

// The weight of the ring about a side's point blended with a lens's own (FocusGroup::blend), at
// log zoom L: `near` (0 to 1) as the lens nears the side, shifted towards the ring that fits more
// (`slid`, the lens's own, and `touching`, each over e^L) over kBlendLog in the logs of their
// shares of L (a ring that fits no zoom has no weight, whatever the zoom; where both fit, neither
// is preferred), and at least `snap`: a smoothstep, continuous in each.
double blend_weight(double slid, double touching, double near, double snap, double log_zoom) {
  auto share = [&](double fit) { return std::clamp(1 + std::log(fit) / log_zoom, 0.0, 1.0); };
  const double a = share(slid), b = share(touching);
  const double apart = a > 0 && b > 0 ? std::log(b / a) : touching > slid ? HUGE_VAL : -HUGE_VAL;
  return std::max(snap, Rim::fade(apart / kBlendLog + near));
}

// Blends the ring of `other` into g's with weight t in (0, 1), each ring at the zoom, or where
// one falls short (its fit over the zoom `slid` for g's, `touching` for other's below 1), at its
// fit and the other the more; where their weighed fits fall short of the zoom, both beyond their
// fits in proportion (group_fit bounds how far).
void blend_into(FocusGroup& g, FocusGroup other, double t, double slid, double touching) {
  const double mean = (1 - t) * slid + t * touching;
  g.blend = std::make_shared<const FocusGroup>(std::move(other));
  g.blend_weight = t;
  g.blend_zoom = mean < 1       ? touching / mean
                 : touching < 1 ? touching
                 : slid < 1     ? (1 - (1 - t) * slid) / t
                                : 1.0;
}

// A lens alone off every side but nearer one than kSideReach times its reach r is magnified
// either by its ring about its centre, a circle's focus sliding away from the side
// (Ring::least_slide), or by the ring about the side's point nearest its centre, as if it touched
// the side (the ring a region over that side has, so the zoom is continuous where it touches it),
// its focus sliding along the side. One over one side, or magnified about its point, is
// magnified the same way near a second side: by its ring about that point, sliding along the
// first side, or by the ring about their corner (the ring a region over both has). Within
// kSideSnap r of the side, by the second (the slide off the side stretched the thin gap until the
// mesh folded: a circle a fifth of a pixel off the side fitted 1.0). Beyond, each is held to a zoom
// continuous with the other's: the slide to what the ring about the side's point fits times psi =
// e^(kSideRamp (gap / r - kSideSnap)) (that ring measured with the footprint it would have at
// the held zoom: a footprint twice the zoom held to psi times its fit at the group's footprint
// gave a zoom of psi^5 times), that ring to what the slide fits times 8^w, w falling from 1 at
// kSideBand r to 0 at kSideReach r, so it adds nothing where it comes in (held to 8^(w - 1) times
// its own fit instead, it left the zoom of a circle along a side into a corner at 1.86-2.3 between
// places that got 3, and changed it by up to ln 8 / r of itself a pixel). The zoom obtained, the
// largest that fits, is the larger of the two held fits, continuous in the circle's place, size
// and zoom; the least of it and the zoom is FocusGroup::most_zoom. The warp blends the two rings
// (FocusGroup::blend): the weight of the ring about the side's point rises smoothly as a
// circle's slide moves its focus towards where that ring would, shifts towards the ring that
// fits more, and is 1 from kSideSnap r of the side for a lens that slides, whatever the fits
// (where one ring gave way to the other at once, the magnified focus moved by up to 112 px in a
// pixel's drag: a circle r 45 at zoom 3.46, 31 px from the left side of 1024 x 768). Returns the
// zoom the choice fits over the group's, held, where the choice found it; nothing where g is as it
// was or its ring tells it. No ring's margin exceeds `most_margin`.
std::optional<double> magnify_near_side(FocusGroup& g, const Eigen::AlignedBox2d& bounds,
                                        double ratio, const std::vector<Lens>& lenses, double width,
                                        double height, double most_margin, const FitMesh& mesh) {
  // Its rings on the mesh (one that follows the regions, cell 0: the cell sets only search steps).
  const double cell = mesh.cell > 0 ? mesh.cell : g.reach;
  std::array<double, 4> gaps = {bounds.min().x(), width - bounds.max().x(), bounds.min().y(),
                                height - bounds.max().y()};
  // A group about a side's point is near only the two sides across it; the point it is
  // magnified about unmoved is its centre's nearest on that side.
  Eigen::Vector2d unmoved = g.centre;
  if (g.on_side) {
    const size_t on = g.fixed.x() == 0 || g.fixed.x() == width ? 0 : 2;
    gaps[on] = gaps[on + 1] = std::numeric_limits<double>::infinity();
    unmoved[on / 2] = g.fixed[on / 2];
  }
  const size_t side = size_t(std::min_element(gaps.begin(), gaps.end()) - gaps.begin());
  const double gap = gaps[side] / g.reach;
  if (!(gap < kSideReach)) return std::nullopt;
  const bool corner = g.on_side;  // near a second side, the ring about their corner
  FocusGroup at_side = g;
  at_side.fixed[side / 2] = side % 2 == 0 ? 0 : (side < 2 ? width : height);
  at_side.on_side = true;
  at_side.margin = footprint_margin(ratio, g.reach, at_side.fixed - g.centre, most_margin);
  at_side.slides = !corner;  // along the side (a polygon's slide off it folded its corners)
  g.side = at_side.side = (at_side.fixed - g.centre).normalized();
  // The footprint ratio at log zoom L: a footprint that follows the zoom grows with it, so a
  // ring held to a fraction of its fit is held to that fraction of the zoom it gets.
  const bool follows = !(lenses[g.lenses.front()].footprint > 0);
  auto ratio_at = [&](double log_zoom) {
    return follows ? ratio * std::exp(log_zoom - g.log_zoom) : ratio;
  };
  // The same about the side's point, with its choice near the next side (`chosen`, if given).
  auto fit = [&](double log_zoom, FocusGroup* chosen = nullptr) {
    FocusGroup local = at_side;
    FocusGroup& at = chosen ? (*chosen = at_side) : local;
    at.log_zoom = log_zoom;
    at.margin = footprint_margin(ratio_at(log_zoom), g.reach, at.fixed - g.centre, most_margin);
    if (!corner)
      if (const std::optional<double> held = magnify_near_side(
              at, bounds, ratio_at(log_zoom), lenses, width, height, most_margin, mesh))
        return *held;
    return fit_over(Ring(at, lenses, cell, mesh.band, width, height), log_zoom);
  };
  // Magnifies g about the side's point and chooses near the next side (as fit did: touched).
  std::optional<FocusGroup> touched;
  auto take_side = [&]() -> std::optional<double> {
    g = touched.value_or(at_side);
    if (corner || touched) return std::nullopt;
    return magnify_near_side(g, bounds, ratio, lenses, width, height, most_margin, mesh);
  };
  if (gap < kSideSnap && g.slides) return take_side();
  const double log_psi = kSideRamp * (gap - kSideSnap);
  const double w = std::clamp((kSideReach - gap) / (kSideReach - kSideBand), 0.0, 1.0);
  // The slide (a polygon's or a mask's ring about its centre, unslid), held: it fits at L and
  // the ring about the side's point at L - ln psi (rings are found only where needed: 720 rays).
  const Ring sliding(g, lenses, cell, mesh.band, width, height);
  const double off = fit_over(sliding, g.log_zoom);
  const double slid = off < 1 - kFitTolerance ? off : std::min(off, fit(g.log_zoom - log_psi));
  // The ring about the side's point is blended in as the slide moves the focus kBlendFrom to
  // kSideSlide of the way to where that ring would (none where it is first tried: a slide along
  // a side away from a corner blended the corner's ring in at once), and from 2 kSideSnap r to
  // kSideSnap r off the side for a lens that slides, whatever the fits (blend_weight).
  const Eigen::Vector2d to_side = at_side.fixed - unmoved;
  const double travel = (g.fixed - sliding.pull - unmoved).dot(to_side) / to_side.squaredNorm();
  const double near =
      Rim::fade((travel - kBlendFrom) / (kSideSlide - kBlendFrom)) * Rim::fade(2 * w);
  const double snap = g.slides ? Rim::fade((2 * kSideSnap - gap) / kSideSnap) : 0.0;
  if (slid >= 1 - kFitTolerance && near == 0 && snap == 0) return slid;
  const double touching =  // the ring about the side's point, held
      w > 0 ? std::min(fit(g.log_zoom, &touched.emplace()), slid * std::pow(8.0, w)) : 0.0;
  const double t = blend_weight(slid, touching, near, snap, g.log_zoom);
  if (t == 1) take_side();
  if (t > 0 && t < 1) blend_into(g, touched.value_or(at_side), t, slid, touching);
  // The zoom that fits: the larger held fit (continuous where one gives way to the other), the
  // slide's where it alone has weight; where it falls short, fitting_zooms finds it so.
  const double fits = t == 0 ? slid : std::max(slid, touching);
  if (fits < 1 - kFitTolerance || g.blend)
    g.most_zoom = std::min(g.most_zoom, std::exp(g.log_zoom) * fits);
  return fits;
}

// The group of lenses `members` at `log_zooms`, with the margin of its own footprint, at most
// `most_margin` (the room a neighbour leaves it, share_room).
FocusGroup make_group(std::vector<size_t> members, const std::vector<Lens>& lenses,
                      const std::vector<double>& log_zooms, double width, double height,
                      const FitMesh& mesh,
                      double most_margin = std::numeric_limits<double>::infinity()) {
  FocusGroup g;
  g.lenses = std::move(members);
  Eigen::AlignedBox2d peaks;
  double ratio = 0;
  for (size_t k : g.lenses) {
    peaks.extend(lenses[k].region.peak());
    ratio = std::max(ratio, footprint_ratio(lenses[k]));
    g.log_zoom = std::max(g.log_zoom, log_zooms[k]);
  }
  g.centre = g.lenses.size() == 1 ? lenses[g.lenses[0]].region.peak() : peaks.center();
  Eigen::AlignedBox2d bounds;
  for (size_t k : g.lenses) {
    g.reach =
        std::max(g.reach, (lenses[k].region.peak() - g.centre).norm() + lenses[k].region.reach());
    bounds.extend(lenses[k].region.bounds());
  }
  // A region over an image side is magnified about a point on that side, so the side stays.
  g.fixed = g.centre;
  if (bounds.min().x() <= 0) g.fixed.x() = 0;
  if (bounds.max().x() >= width) g.fixed.x() = width;
  if (bounds.min().y() <= 0) g.fixed.y() = 0;
  if (bounds.max().y() >= height) g.fixed.y() = height;
  const int sides = (bounds.min().x() <= 0) + (bounds.max().x() >= width) +
                    (bounds.min().y() <= 0) + (bounds.max().y() >= height);
  g.on_side = sides > 0;
  g.slides = sides <= 1 && (std::all_of(g.lenses.begin(), g.lenses.end(),
                                        [&](size_t k) { return lenses[k].region.circle(); }) ||
                            (sides == 1 && g.lenses.size() == 1));
  // The footprint, the focus scaled by the ratio about that point, lies within the disk of
  // radius ratio (reach + |fixed - centre|) - |fixed - centre| about the centre. A focus near a
  // side slides away from it (Ring::least_slide), magnified about a point between the centre
  // and that side; its footprint grows the same way, with the point estimated_fixed_offset puts
  // there (the side's point where the region touches it, so the footprint does not jump).
  const Eigen::Vector2d offset =
      g.slides && !g.on_side ? estimated_fixed_offset(g.centre, bounds, g.log_zoom, width, height)
                             : Eigen::Vector2d(g.fixed - g.centre);
  g.margin = footprint_margin(ratio, g.reach, offset, most_margin);
  if (sides <= 1 && g.lenses.size() == 1 && g.log_zoom > 0)
    magnify_near_side(g, bounds, ratio, lenses, width, height, most_margin, mesh);
  return g;
}

// Where the disks of radius reach + margin of two groups overlap (a blend's the larger of its
// rings', FocusGroup::disk_radius), the room between their foci (which do not overlap) is
// shared: each is given what its ring needs at its zoom on the ray towards the other
// (ring_need) and half of what is left, or less where the other needs more, and never more than
// its own margin. The margins of a pair then sum to at most the room, every margin is a
// continuous function of the groups' places and zooms, and a group's is the least over its
// neighbours, whatever their order. Neither wide footprints (of a lens near a side) nor high
// requests take a neighbour's room beyond half of what both leave. Returns each group's most
// margin (infinite where no neighbour shrinks it); a lens alone near a side is made again with
// it (focus_groups), so its choice of rings sees the room it has.
std::vector<double> share_room(std::vector<FocusGroup>& groups) {
  const size_t n = groups.size();
  std::vector<double> own(n), most(n, std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < n; ++i) own[i] = groups[i].disk_radius() - groups[i].reach;
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      FocusGroup &a = groups[i], &b = groups[j];
      const double room = std::max((a.centre - b.centre).norm() - a.reach - b.reach, 0.0);
      if (own[i] + own[j] <= room) continue;
      const double need_a = std::min(own[i], ring_need(a.reach, a.log_zoom)),
                   need_b = std::min(own[j], ring_need(b.reach, b.log_zoom));
      const double half_left = 0.5 * (room - need_a - need_b);
      const double offer_a = std::clamp(std::min(own[i], need_a + half_left), 0.0, room),
                   offer_b = std::clamp(std::min(own[j], need_b + half_left), 0.0, room);
      if (room - offer_b < std::min(most[i], own[i])) a.neighbour = int(b.lenses.front());
      if (room - offer_a < std::min(most[j], own[j])) b.neighbour = int(a.lenses.front());
      most[i] = std::min(most[i], room - offer_b);
      most[j] = std::min(most[j], room - offer_a);
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (!(most[i] < own[i])) most[i] = std::numeric_limits<double>::infinity();
    groups[i].margin = std::min(groups[i].margin, most[i]);
  }
  return most;
}

}  // namespace

double ring_need(double reach, double log_zoom) {
  return reach * std::expm1(log_zoom / kFitExponent);
}

std::vector<FocusGroup> focus_groups(const std::vector<Lens>& lenses,
                                     const std::vector<double>& log_zooms, double width,
                                     double height, const FitMesh& mesh) {
  require(log_zooms.size() == lenses.size(), "focus_groups", "one log zoom per lens expected");
  const size_t n = lenses.size();
  // Union-find over the pairs whose rings would not fit side by side: disks of reach x
  // zoom^1.25 (reach + ring_need) about their peaks overlap (shared_room_zooms gives lenses near
  // each other zooms at which that holds exactly where they are better magnified as one).
  std::vector<size_t> root(n);
  for (size_t k = 0; k < n; ++k) root[k] = k;
  auto find = [&](size_t k) {
    while (root[k] != k) k = root[k] = root[root[k]];
    return k;
  };
  // Each lens's peak and ring's reach once: the pairs are n^2 (200 lenses, searched for their
  // fits, spent most of their time here).
  std::vector<Eigen::Vector2d> peak(n);
  std::vector<double> ringed(n);
  for (size_t k = 0; k < n; ++k) {
    peak[k] = lenses[k].region.peak();
    ringed[k] = lenses[k].region.reach() + ring_need(lenses[k].region.reach(), log_zooms[k]);
  }
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      if ((peak[i] - peak[j]).norm() < ringed[i] + ringed[j]) root[find(i)] = find(j);
  std::vector<std::vector<size_t>> members;
  std::vector<int> index(n, -1);
  for (size_t k = 0; k < n; ++k) {
    int& g = index[find(k)];
    if (g < 0) {
      g = int(members.size());
      members.emplace_back();
    }
    members[size_t(g)].push_back(k);
  }
  std::vector<FocusGroup> groups;
  for (std::vector<size_t>& m : members)
    groups.push_back(make_group(std::move(m), lenses, log_zooms, width, height, mesh));
  const std::vector<double> most = share_room(groups);
  for (size_t i = 0; i < groups.size(); ++i) {
    if (groups[i].lenses.size() > 1 || !std::isfinite(most[i])) continue;
    const int neighbour = groups[i].neighbour;
    groups[i] = make_group(groups[i].lenses, lenses, log_zooms, width, height, mesh, most[i]);
    groups[i].neighbour = neighbour;
  }
  return groups;
}

namespace {
std::vector<double> own_log_zooms(const std::vector<Lens>& lenses) {
  std::vector<double> log_zooms;
  for (const Lens& lens : lenses) log_zooms.push_back(std::log(lens.zoom));
  return log_zooms;
}
}  // namespace

FocusGroup focus_group_of(const std::vector<Lens>& lenses, double width, double height,
                          const FitMesh& mesh) {
  require(!lenses.empty(), "focus_group_of", "no lenses");
  std::vector<size_t> all(lenses.size());
  for (size_t k = 0; k < lenses.size(); ++k) all[k] = k;
  return make_group(std::move(all), lenses, own_log_zooms(lenses), width, height, mesh);
}

std::vector<FocusGroup> focus_groups(const std::vector<Lens>& lenses, double width, double height,
                                     const FitMesh& mesh) {
  return focus_groups(lenses, own_log_zooms(lenses), width, height, mesh);
}

double FocusGroup::disk_radius() const {
  return std::max(reach + margin, blend ? blend->disk_radius() : 0.0);
}

bool footprint_clear_of_border(const FocusGroup& group, double width, double height) {
  // smooth_min rounds the footprint's edge where the border is nearer than 9/7 of the edge.
  const double room = 1.3 * group.disk_radius();
  return group.centre.x() >= room && group.centre.y() >= room && width - group.centre.x() >= room &&
         height - group.centre.y() >= room;
}

double radial_distortion_bound(double zoom, double ratio) {
  require(std::isfinite(zoom) && zoom >= 1 && std::isfinite(ratio) && ratio > 1,
          "radial_distortion_bound",
          "need zoom >= 1 and ratio > 1, got " + std::to_string(zoom) + " and " +
              std::to_string(ratio));
  const double k = 1 - std::log(zoom) / std::log(ratio);
  return k > 0 ? 1 / k - 1 : std::numeric_limits<double>::infinity();
}

double rim_distortion_bound(double zoom, double ratio) {
  const double power = radial_distortion_bound(zoom, ratio);
  if (!std::isfinite(power)) return power;
  const Rim rim(std::log(zoom) / std::log(ratio));
  return (1 + rim.b * rim.a) * (1 + power) - 1;
}

namespace {
// The zoom a group fits on a mesh of cell side `cell` whose foci are held `band` wider, at most
// its most zoom, and what bounds the ring that limits it. A blend (FocusGroup::blend) fits
// where each ring fits the zoom it is given (the blend's shares of the zoom were found on a mesh
// that follows the regions), the ring of weight w short of it by at most kBlendBeyond + kBlendSlack
// (1 - w) / w of it (so a ring that comes in with a small weight does not make the zoom jump, and
// the blend's radial scale, a weighed sum of its rings', stays positive).
struct GroupFit {
  double zoom;
  Ring::Room room;
  Eigen::Vector2d centre;  // of the ring that limits it
};
GroupFit group_fit(const FocusGroup& group, const std::vector<Lens>& lenses, double cell,
                   double band, double width, double height) {
  constexpr double kBlendSlack = 0.1, kBlendBeyond = 0.05;
  const Warp warp(group, lenses, cell, band, width, height);
  GroupFit out{std::numeric_limits<double>::infinity(), {}, group.centre};
  for (const Warp::Part& part : warp.parts) {
    const double log_zoom = group.log_zoom + part.log_share;
    const Ring::Room room = part.ring.min_ratio(log_zoom);
    const double fit = group.blend
                           ? std::exp(group.log_zoom) *
                                 (zoom_of_room(room.ratio) / std::exp(log_zoom) + kBlendBeyond +
                                  kBlendSlack * (1 - part.weight) / part.weight)
                           : zoom_of_room(room.ratio);
    if (fit < out.zoom) out = {fit, room, part.ring.centre};
  }
  // Held (a lens near a side).
  if (group.most_zoom < out.zoom) {
    out.zoom = group.most_zoom;
    out.room.by = Ring::Room::By::kSide;
    out.room.u = group.side;
  }
  return out;
}
}  // namespace

double group_fitting_zoom(const FocusGroup& group, const std::vector<Lens>& lenses, double cell,
                          double band, double width, double height) {
  return group_fit(group, lenses, cell, band, width, height).zoom;
}

std::vector<double> fitting_zooms(const std::vector<Lens>& lenses, double cell, double band,
                                  double width, double height, std::vector<std::string>* reasons,
                                  const std::vector<size_t>* only, const Eigen::Vector2d& stretch) {
  std::vector<double> fits(lenses.size());
  if (reasons) reasons->assign(lenses.size(), "");
  for (const FocusGroup& group : focus_groups(lenses, width, height, {cell, band})) {
    if (only && std::none_of(group.lenses.begin(), group.lenses.end(), [&](size_t k) {
          return std::find(only->begin(), only->end(), k) != only->end();
        }))
      continue;
    const GroupFit fit = group_fit(group, lenses, cell, band, width, height);
    const Ring::Room& room = fit.room;
    for (size_t k : group.lenses) fits[k] = fit.zoom;
    if (!reasons) continue;
    std::string why;
    if (room.by == Ring::Room::By::kSide) {
      // The side the ray leaves by, and how far the group's regions are from it.
      Eigen::AlignedBox2d b;
      for (size_t k : group.lenses) b.extend(lenses[k].region.bounds());
      const Eigen::Vector2d exits = ray_exits(fit.centre, room.u, width, height);
      const bool vertical = exits.x() < exits.y();
      const char* side =
          vertical ? (room.u.x() > 0 ? "right" : "left") : (room.u.y() > 0 ? "bottom" : "top");
      const double gap = vertical
                             ? (room.u.x() > 0 ? width - b.max().x() : b.min().x()) / stretch.x()
                             : (room.u.y() > 0 ? height - b.max().y() : b.min().y()) / stretch.y();
      why = "the image's " + std::string(side) + " side, " +
            std::to_string(int(std::lround(std::max(gap, 0.0)))) +
            " px from the region (a lens farther from it or smaller fits more)";
    } else if (room.by == Ring::Room::By::kDisk && group.neighbour >= 0) {
      why = beside_reason(size_t(group.neighbour));
    } else {
      why = "its footprint (a larger footprint ratio fits more)";
    }
    for (size_t k : group.lenses) {
      // A merged group's lenses are magnified as one focus: say with which.
      std::string with;
      for (size_t j : group.lenses)
        if (j != k) with += (with.empty() ? "" : ", ") + std::to_string(j + 1);
      (*reasons)[k] = with.empty() ? why
                                   : why + "; magnified as one with lens " + with +
                                         " (their rings would not fit side by side)";
    }
  }
  return fits;
}

FocusField focus_field(const Eigen::MatrixX2d& V, const std::vector<Lens>& lenses,
                       const std::vector<double>& log_zooms, double cell, double band, double width,
                       double height, ThreadPool& pool, double slack) {
  require(log_zooms.size() == lenses.size(), "focus_field", "one log zoom per lens expected");
  require(std::isfinite(cell) && cell > 0 && std::isfinite(band) && band >= 0 &&
              std::isfinite(slack) && slack >= 1,
          "focus_field", "cell must be > 0, band >= 0 and slack >= 1");
  for (double z : log_zooms)
    require(std::isfinite(z) && z >= 0, "focus_field",
            "log zoom must be finite and >= 0, got " + std::to_string(z));
  const Eigen::Index n = V.rows();
  FocusField out;
  out.groups = focus_groups(lenses, log_zooms, width, height, {cell, band});
  std::vector<Warp> warps;
  for (const FocusGroup& g : out.groups) warps.emplace_back(g, lenses, cell, band, width, height);
  FocusConstraints& c = out.constraints;
  c.focus.assign(size_t(n), -1);
  c.pinned.assign(size_t(n), 1);
  c.anisotropy = Eigen::VectorXd::Ones(n);
  out.log_scale = Eigen::VectorXd::Zero(n);
  out.level = Eigen::VectorXd::Zero(n);
  out.start = V;
  parallel_for(pool, size_t(n), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const Eigen::Vector2d p = V.row(Eigen::Index(i)).transpose();
      // The nearest focus, and the warp p is deepest in (smallest s over edge).
      double nearest = std::numeric_limits<double>::infinity(), deepest = 1;
      int closest = -1;
      size_t owner = 0;
      Warp::Place owner_place;
      for (size_t g = 0; g < out.groups.size(); ++g) {
        Warp::Place place = warps[g].place(p);
        if (place.distance < nearest) nearest = place.distance, closest = int(g);
        if (place.depth < deepest) {
          deepest = place.depth;
          owner = g;
          owner_place = std::move(place);
        }
      }
      c.pinned[i] = deepest == 1;
      if (nearest <= band) {
        c.focus[i] = closest;
        out.log_scale(Eigen::Index(i)) = out.groups[size_t(closest)].log_zoom;
      }
      if (!c.pinned[i]) {
        // The distortion of its ring at this vertex (the ratio of its radial to its tangential
        // scale, or its inverse where the slid ring stretches along the ray; 1 at the footprint's
        // edge, so the solve keeps the rim without a crease), with
        // the slack; a ray too short for the zoom has no radial solution: the bound then only
        // keeps the context from folding over itself (at most 20, a sliver).
        const double log_zoom = out.groups[owner].log_zoom;
        c.anisotropy(Eigen::Index(i)) =
            std::min(slack * warps[owner].distortion(owner_place, log_zoom), 20.0);
        if (log_zoom > 0 && warps[owner].moves(owner_place))
          out.start.row(Eigen::Index(i)) = warps[owner].moved(p, owner_place, log_zoom).transpose();
      }
      out.level(Eigen::Index(i)) = c.pinned[i] ? 0.0 : 1.0;
    }
  });
  return out;
}

namespace {

// Moves the rows of X (pixels) by a group's `warp` (see focus_start) at `log_zoom`.
void apply_warp(Eigen::MatrixX2d& X, const Warp& warp, double log_zoom, ThreadPool& pool) {
  if (log_zoom <= 0) return;
  parallel_for(pool, size_t(X.rows()), [&](size_t begin, size_t end) {
    for (Eigen::Index i = Eigen::Index(begin); i < Eigen::Index(end); ++i) {
      const Eigen::Vector2d q = X.row(i).transpose();
      const Warp::Place p = warp.place(q);
      if (warp.moves(p)) X.row(i) = warp.moved(q, p, log_zoom).transpose();
    }
  });
}

// Twice the signed area of triangle f of F (#F x 3) at the points P (#V x 2, pixels): positive
// for a counter-clockwise triangle.
double area2(const Eigen::MatrixX2d& P, const Eigen::MatrixX3i& F, Eigen::Index f) {
  const Eigen::Vector2d a = P.row(F(f, 0)), b = P.row(F(f, 1)), c = P.row(F(f, 2));
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// One way of unfolding the start X of mesh (V, F) (cell side `cell`, pixels) where its
// triangles fold though the continuous start does not (relax_folds), for a few rounds: the
// vertices of folded triangles that are neither in a focus (within `band` of a region) nor
// unmoved go to the mean of their neighbours for the first half of the rounds, and half way back
// to their source places in the rest; with `slivers_back`, a sliver's (a triangle of under a
// thousandth of a cell's area in the source) go back from the first round. Returns the folds
// left.
int unfold(Eigen::MatrixX2d& X, const Eigen::MatrixX2d& V, const Eigen::MatrixX3i& F,
           const std::vector<Lens>& lenses, double cell, double band, bool slivers_back) {
  constexpr int kRounds = 16, kMeanRounds = 8;
  const double sliver = 2e-3 * cell * cell;  // twice a thousandth of a cell's area
  auto movable = [&](Eigen::Index i) {
    if (X.row(i) == V.row(i)) return false;
    for (const Lens& lens : lenses)
      if (lens.region.distance(V.row(i).transpose()) <= band) return false;
    return true;
  };
  // The triangles at each vertex, in increasing order (made on the first fold), and the
  // triangles that may be folded in a round: every one in the first, then those folded or at a
  // vertex moved in the round before (no other changed), in increasing order, so each round
  // finds what a look at every triangle would, in the same order.
  std::vector<std::vector<Eigen::Index>> at;
  std::vector<Eigen::Index> candidates;
  for (int round = 0;; ++round) {
    std::vector<Eigen::Index> moved, back, folded;
    auto look = [&](Eigen::Index f) {
      if (area2(X, F, f) > 0) return;
      folded.push_back(f);
      const bool goes_back = round >= kMeanRounds || (slivers_back && area2(V, F, f) < sliver);
      for (int k = 0; k < 3; ++k) (goes_back ? back : moved).push_back(F(f, k));
    };
    if (round == 0)
      for (Eigen::Index f = 0; f < F.rows(); ++f) look(f);
    else
      for (const Eigen::Index f : candidates) look(f);
    const int folds = int(folded.size());
    if (folds == 0 || round == kRounds) return folds;
    if (at.empty()) {
      at.resize(size_t(X.rows()));
      for (Eigen::Index f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) at[size_t(F(f, k))].push_back(f);
    }
    for (std::vector<Eigen::Index>* list : {&moved, &back}) {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
      std::erase_if(*list, [&](Eigen::Index i) { return !movable(i); });
    }
    for (const Eigen::Index i : back) X.row(i) = 0.5 * (X.row(i) + V.row(i));
    // The mean of each moved vertex's neighbours (each edge counted once per triangle side).
    Eigen::MatrixX2d sum = Eigen::MatrixX2d::Zero(Eigen::Index(moved.size()), 2);
    Eigen::VectorXd count = Eigen::VectorXd::Zero(Eigen::Index(moved.size()));
    for (size_t j = 0; j < moved.size(); ++j) {
      for (const Eigen::Index f : at[size_t(moved[j])]) {
        const int k = F(f, 0) == moved[j] ? 0 : F(f, 1) == moved[j] ? 1 : 2;
        sum.row(Eigen::Index(j)) += X.row(F(f, (k + 1) % 3)) + X.row(F(f, (k + 2) % 3));
        count(Eigen::Index(j)) += 2;
      }
    }
    for (size_t j = 0; j < moved.size(); ++j)
      X.row(moved[j]) = sum.row(Eigen::Index(j)) / count(Eigen::Index(j));
    candidates = std::move(folded);
    for (const std::vector<Eigen::Index>* list : {&moved, &back})
      for (const Eigen::Index i : *list)
        candidates.insert(candidates.end(), at[size_t(i)].begin(), at[size_t(i)].end());
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  }
}

// Unfolds the start X of mesh (V, F) where its triangles fold though the continuous start does
// not. Near a polygon's corner the start has a cone (a point's shift grows with its distance
// from the corner), and a triangle that spans a wide angle as seen from the corner folds under
// the cone's linear average on a fine mesh: its vertices go to their neighbours' mean. Where a
// footprint's edge meets an image side at a glancing angle, the ring's edge turns fast from ray
// to ray and the mesh that follows it has slivers a thousandth of a px high, with a vertex on
// the edge (unmoved) and one just inside that the ring moves by more than that: their vertices
// going half way back to their source places unfolds them where the mean may not. Neither way
// unfolds every such fold (the mean spreads a sliver's fold to the triangles around, and going
// back first fails where the mean would have done): each alone left a circle r 24 at zoom 3
// dragged along the top side of a 320 x 240 picture, 6 or 15 px below it, a few places where it
// got 2.41 for "the mesh" between places that got 3. So the mean is tried first, and where it
// leaves a fold, slivers back first from X as it came. Returns the folds left.
int relax_folds(Eigen::MatrixX2d& X, const Eigen::MatrixX2d& V, const Eigen::MatrixX3i& F,
                const std::vector<Lens>& lenses, double cell, double band) {
  const Eigen::MatrixX2d unrepaired = X;
  const int folds = unfold(X, V, F, lenses, cell, band, false);
  if (folds == 0) return 0;
  Eigen::MatrixX2d other = unrepaired;
  const int other_folds = unfold(other, V, F, lenses, cell, band, true);
  if (other_folds >= folds) return folds;
  X = std::move(other);
  return other_folds;
}

}  // namespace

std::function<Eigen::MatrixX2d(const Eigen::MatrixX2d&)> focus_map(
    const std::vector<Lens>& lenses, const std::vector<FocusGroup>& groups, double cell,
    double band, double width, double height, ThreadPool& pool) {
  auto warps = std::make_shared<std::vector<Warp>>();
  for (const FocusGroup& group : groups)
    warps->emplace_back(group, lenses, cell, band, width, height);
  return [warps, groups, &pool](const Eigen::MatrixX2d& points) {
    Eigen::MatrixX2d X = points;
    for (size_t g = 0; g < groups.size(); ++g) apply_warp(X, (*warps)[g], groups[g].log_zoom, pool);
    return X;
  };
}

std::optional<Eigen::MatrixX2d> moved_focus_mesh(const PlanarMesh& mesh,
                                                 const std::vector<int>& on_curve,
                                                 const std::vector<Lens>& from,
                                                 const Eigen::AlignedBox2d& from_box,
                                                 double from_cell, const std::vector<Lens>& to,
                                                 const Eigen::AlignedBox2d& to_box, double to_cell,
                                                 double width, double height, ThreadPool& pool) {
  require(from.size() == to.size() && !from.empty() && on_curve.size() == size_t(mesh.V.rows()),
          "moved_focus_mesh", "the same lenses, and a curve index per vertex, expected");
  const double from_band = focus_band(from, from_cell), to_band = focus_band(to, to_cell);
  const std::vector<FocusGroup> was = focus_groups(from, width, height, {from_cell, from_band}),
                                now = focus_groups(to, width, height, {to_cell, to_band});
  require(was.size() == now.size(), "moved_focus_mesh", "the lenses must keep their groups");
  std::vector<Ring> rings_was, rings_now;
  for (size_t g = 0; g < was.size(); ++g) {
    if (was[g].blend || now[g].blend) return std::nullopt;  // two rings: meshed anew
    rings_was.emplace_back(was[g], from, from_cell, from_band, width, height);
    rings_now.emplace_back(now[g], to, to_cell, to_band, width, height);
  }
  const Eigen::Vector2d shift = to[0].region.peak() - from[0].region.peak();
  const Eigen::Array2d stretch = to_box.sizes().array() / from_box.sizes().array();
  const double near = 2 * to_cell;
  const int regions = int(from.size());  // focus_curves: the regions', then the footprints'
  Eigen::MatrixX2d V(mesh.V.rows(), 2);
  parallel_for(pool, size_t(V.rows()), [&](size_t begin, size_t end) {
    for (Eigen::Index i = Eigen::Index(begin); i < Eigen::Index(end); ++i) {
      const Eigen::Vector2d p = mesh.V.row(i).transpose();
      const Eigen::Vector2d boxed = to_box.min().array() + (p - from_box.min()).array() * stretch;
      // The group whose footprint p is deepest in, or nearest outside of.
      size_t g = was.size();
      Ring::Place at;
      double key = std::numeric_limits<double>::infinity();
      for (size_t k = 0; k < was.size(); ++k) {
        if (was[k].log_zoom <= 0) continue;  // nothing moves
        const Ring::Place place = rings_was[k].place(p);
        if ((place.s - place.edge) / place.edge < key) {
          key = (place.s - place.edge) / place.edge;
          g = k;
          at = place;
        }
      }
      V.row(i) = boxed.transpose();  // where p is beyond every footprint
      if (g == was.size()) continue;
      // Along its ray from the ring's centre p keeps its place between the focus and the
      // footprint's edge (rho = (s - inner) / (edge - inner)), where the edge moved to:
      // rigidly in a focus, with the edge at it, and so along the border where the edge is the
      // border; beyond the edge it turns, within `near`, to the box's stretch.
      const double level = at.s - at.edge;
      const double rho = at.edge > at.inner ? (at.s - at.inner) / (at.edge - at.inner) : 0.0;
      const double moved = rings_now[g].edge(at.u) - at.edge;
      const Eigen::Vector2d ringed = p + shift + std::clamp(rho, 0.0, 1.0) * moved * at.u;
      const double w = level <= 0 ? 1.0 : std::max(0.0, 1 - level / near);
      Eigen::Vector2d q = w * ringed + (1 - w) * boxed;
      // A vertex on a side of the box slides along it (where the footprint's edge runs along the
      // border, with its neighbours on the edge).
      const uint8_t sides = mesh.sides[size_t(i)];
      if (sides & (kLeft | kRight)) q.x() = boxed.x();
      if (sides & (kTop | kBottom)) q.y() = boxed.y();
      if (on_curve[size_t(i)] >= regions && sides == 0) {
        // Onto the moved edge, but not onto the image border where the edge runs along it (a
        // triangle with a side there would vanish): at least a thousandth of a cell inside it.
        const double margin = 1e-3 * to_cell;
        q = rings_now[g]
                .onto_edge(q)
                .cwiseMax(Eigen::Vector2d::Constant(margin))
                .cwiseMin(Eigen::Vector2d(width - margin, height - margin));
      }
      V.row(i) = q.transpose();
    }
  });
  // (A sliver, below a hundredth of a cell's area, as the curves cut beside the border where a
  // footprint's edge runs a hair inside it, may shrink further, but not fold or vanish.)
  const double sliver = 1e-2 * to_cell * to_cell;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const double before = area2(mesh.V, mesh.F, f), now = area2(V, mesh.F, f);
    if (!(now > 0 && (now > 0.2 * before || before < sliver))) return std::nullopt;
  }
  return V;
}

Eigen::MatrixX2d focus_start(const PlanarMesh& mesh, const std::vector<Lens>& lenses,
                             const std::vector<FocusGroup>& groups, double cell, double band,
                             double width, double height, ThreadPool& pool) {
  Eigen::MatrixX2d X = focus_map(lenses, groups, cell, band, width, height, pool)(mesh.V);
  relax_folds(X, mesh.V, mesh.F, lenses, cell, band);
  return X;
}

std::vector<double> unfolding_zooms(const PlanarMesh& mesh, const std::vector<Lens>& lenses,
                                    double cell, double band, double width, double height,
                                    ThreadPool& pool) {
  std::vector<double> zooms(lenses.size(), 1.0);
  for (const FocusGroup& group : focus_groups(lenses, width, height, {cell, band})) {
    // The footprints are disjoint, so each group is tried on its own.
    const Warp warp(group, lenses, cell, band, width, height);
    for (const double fraction : kZoomFractions) {
      Eigen::MatrixX2d X = mesh.V;
      apply_warp(X, warp, fraction * group.log_zoom, pool);
      if (relax_folds(X, mesh.V, mesh.F, lenses, cell, band) > 0) continue;
      for (size_t k : group.lenses) zooms[k] = std::exp(fraction * group.log_zoom);
      break;
    }
  }
  return zooms;
}

FlattenResult flatten_focus(Flattener& flattener, const PlanarMesh& mesh,
                            const std::vector<Lens>& lenses, const FocusField& field, double cell,
                            double band, double width, double height, ThreadPool& pool,
                            const SolveControl* control) {
  // The full start, else one at lower zooms (the solve then raises them), else the identity.
  for (const double fraction : kZoomFractions) {
    Eigen::MatrixX2d start;
    if (fraction == 1) {
      start = field.start;
      relax_folds(start, mesh.V, mesh.F, lenses, cell, band);
    } else {
      std::vector<FocusGroup> lowered = field.groups;
      for (FocusGroup& g : lowered) g.log_zoom *= fraction;
      start = focus_start(mesh, lenses, lowered, cell, band, width, height, pool);
    }
    if (!flattener.admissible(start)) continue;
    flattener.admit_anisotropy(start);
    return flattener.solve(start, nullptr, control);
  }
  return flattener.solve(mesh.V, nullptr, control);
}

namespace {

// The sharpest corner of a closed outline, degrees: the angle between the two edges at a vertex,
// a spike's or a notch's alike.
double sharpest_corner(const std::vector<Eigen::Vector2d>& outline) {
  double sharpest = 180;
  const size_t n = outline.size();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = outline[(i + n - 1) % n] - outline[i];
    const Eigen::Vector2d b = outline[(i + 1) % n] - outline[i];
    sharpest = std::min(sharpest, std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b)) *
                                      180 / std::numbers::pi);
  }
  return sharpest;
}

}  // namespace

bool meshed_along_regions(const std::vector<Lens>& lenses, double cell) {
  return std::all_of(lenses.begin(), lenses.end(), [&](const Lens& lens) {
    // A circle of 2 cells or more: one of 1 to 3 was not followed, so its band of 1.4 cells held
    // its footprint's edge closer than the fit needs at any zoom, and two r 10 circles at zoom 2
    // 400 px apart on a 512 px image (5 px cells) were shown unmagnified; of 1.1 to 1.3 cells, the
    // focus of one on a side was magnified 2.69 where solved at 3.2.
    if (lens.region.circle()) return lens.region.size() >= 2 * cell;
    // A corner sharper than kSharpestMeshedCorner (a jagged outline's spikes) is not followed:
    // the mesh made along it had degenerate triangles (random star polygons of 65 to 380
    // vertices, corners of 0.05 to 3.5 degrees: "Flattener: triangle N is degenerate").
    const std::optional<std::vector<Eigen::Vector2d>> outline = lens.region.outline();
    return outline && lens.region.size() >= 1 * cell &&
           sharpest_corner(*outline) >= kSharpestMeshedCorner;
  });
}

double focus_band(const std::vector<Lens>& lenses, double cell) {
  return meshed_along_regions(lenses, cell) ? 1e-6 * cell : std::numbers::sqrt2 * cell;
}

std::vector<MeshCurve> focus_curves(const std::vector<Lens>& lenses, double cell, double band,
                                    double width, double height) {
  std::vector<MeshCurve> curves;
  for (const Lens& lens : lenses) {
    if (const std::optional<Circle> c = lens.region.circle()) {
      curves.push_back(circle_curve(c->center, c->radius));
      curves.back().slope = true;  // the ring bends most next to the focus
    } else if (const std::optional<std::vector<Eigen::Vector2d>> p = lens.region.outline()) {
      curves.push_back(polygon_curve(*p));
    }
  }
  for (const FocusGroup& group : focus_groups(lenses, width, height, {cell, band})) {
    if (group.log_zoom <= 0) continue;  // nothing moves
    auto warp = std::make_shared<const Warp>(group, lenses, cell, band, width, height);
    const Ring& ring = warp->ring();
    if (warp->parts.size() == 1 && ring.inner_.size() == 1 &&
        footprint_clear_of_border(group, width, height)) {
      // A circle about its centre: the footprint's edge is the group's disk.
      curves.push_back(circle_curve(ring.centre, ring.disk_radius));
      continue;
    }
    MeshCurve curve;
    curve.level = [warp](const Eigen::Vector2d& p) { return warp->level(p); };
    curve.project = [warp](const Eigen::Vector2d& p) { return warp->onto_edge(p); };
    for (const Warp::Part& part : warp->parts) {
      const Eigen::Vector2d c = part.ring.centre;
      const double r = part.ring.disk_radius + (c - group.centre).norm();
      curve.bounds.extend(Eigen::AlignedBox2d(c.array() - r, c.array() + r));
    }
    curves.push_back(std::move(curve));
  }
  return curves;
}

}  // namespace geolens
