#include "geometry/conforming_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

#include "geolens/core/errors.h"
#include "geometry/polygon.h"
#include "numerics/bracketed_root.h"
#include "numerics/svd2.h"

namespace geolens {

namespace {

using Triangle = std::array<int, 3>;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// The mesh being made to follow the curves: its vertices, triangles, the triangles at each
// vertex, side flags, and which vertices may no longer move.
struct Work {
  // A vertex closer to a curve than this is on it (pixels): a millionth of the mesh's cell, so
  // that a crossing is never so near a vertex that its triangles are degenerate.
  double on_curve = 0;
  std::vector<Eigen::Vector2d> V;
  std::vector<Triangle> F;
  std::vector<std::vector<int>> around;
  std::vector<uint8_t> sides;
  std::vector<char> locked;
  std::vector<int> curve_of;  // the curve a vertex was placed on, or -1
  Eigen::AlignedBox2d box;    // the mesh's extent: its sides' coordinates

  double area2(const Triangle& t) const {
    return cross(V[size_t(t[1])] - V[size_t(t[0])], V[size_t(t[2])] - V[size_t(t[0])]);
  }

  // The lengths of t's edges, shortest first.
  std::array<double, 3> edge_lengths(const Triangle& t) const {
    std::array<double, 3> l;
    for (size_t k = 0; k < 3; ++k) l[k] = (V[size_t(t[(k + 1) % 3])] - V[size_t(t[k])]).norm();
    std::sort(l.begin(), l.end());
    return l;
  }

  // Moves free vertex i to p, on `curve`, unless a triangle at it would shrink below a fifth of
  // its area (or fold); locks it if moved.
  bool try_move(int i, const Eigen::Vector2d& p, int curve) {
    if (locked[size_t(i)]) return false;
    const Eigen::Vector2d old = V[size_t(i)];
    std::vector<double> before;
    for (int f : around[size_t(i)]) before.push_back(area2(F[size_t(f)]));
    V[size_t(i)] = p;
    for (size_t k = 0; k < before.size(); ++k) {
      if (!(area2(F[size_t(around[size_t(i)][k])]) > 0.2 * before[k])) {
        V[size_t(i)] = old;
        return false;
      }
    }
    locked[size_t(i)] = 1;
    curve_of[size_t(i)] = curve;
    return true;
  }

  // A vertex on a side is placed on it exactly (a crossing computed there was 1e-13 px off, and
  // the flattener, which holds it on the side, then refused a start the ring kept on it).
  int add_vertex(Eigen::Vector2d p, uint8_t side_flags, int curve) {
    if (side_flags & kLeft) p.x() = box.min().x();
    if (side_flags & kRight) p.x() = box.max().x();
    if (side_flags & kTop) p.y() = box.min().y();
    if (side_flags & kBottom) p.y() = box.max().y();
    V.push_back(p);
    sides.push_back(side_flags);
    locked.push_back(1);
    curve_of.push_back(curve);
    around.emplace_back();
    return int(V.size()) - 1;
  }

  // Triangles changed or added since `touched` was last cleared (if it is in use).
  std::vector<char> touched;

  void set_triangle(int f, const Triangle& t) {
    if (!touched.empty()) touched[size_t(f)] = 1;
    for (int v : F[size_t(f)]) {
      std::vector<int>& at = around[size_t(v)];
      at.erase(std::find(at.begin(), at.end(), f));
    }
    F[size_t(f)] = t;
    for (int v : t) around[size_t(v)].push_back(f);
  }

  void add_triangle(const Triangle& t) {
    if (!touched.empty()) touched.push_back(1);
    F.push_back(t);
    for (int v : t) around[size_t(v)].push_back(int(F.size()) - 1);
  }

  // Puts vertex m, on edge a - b, into both triangles of the edge.
  void split_edge(int a, int b, int m) {
    const std::vector<int> holding = around[size_t(a)];
    for (int f : holding) {
      const Triangle t = F[size_t(f)];
      for (int k = 0; k < 3; ++k) {
        const int p = t[size_t(k)], q = t[size_t((k + 1) % 3)], x = t[size_t((k + 2) % 3)];
        if (!((p == a && q == b) || (p == b && q == a))) continue;
        set_triangle(f, {p, m, x});
        add_triangle({m, q, x});
        break;
      }
    }
  }

  // Splits triangle f into three at vertex m, inside it.
  void split_triangle(int f, int m) {
    const Triangle t = F[size_t(f)];
    set_triangle(f, {t[0], t[1], m});
    add_triangle({t[1], t[2], m});
    add_triangle({t[2], t[0], m});
  }

  // Splits every triangle with vertices on both sides of curve number `curve` along it. side(v)
  // is -1, 0 (on the curve) or 1; crossing(a, b) is where the curve crosses edge a - b (ends on
  // opposite sides), or nothing where it does not (a polygon edge's line beyond the edge).
  void cut(int curve, const std::function<int(int)>& side,
           const std::function<std::optional<Eigen::Vector2d>(int, int)>& crossing) {
    std::map<std::pair<int, int>, int> added;  // -1: the edge is not crossed
    auto crossing_vertex = [&](int i, int j) {
      const std::pair<int, int> key = std::minmax(i, j);
      auto [it, inserted] = added.try_emplace(key, -1);
      if (inserted) {
        if (const std::optional<Eigen::Vector2d> p = crossing(key.first, key.second))
          it->second = add_vertex(*p, sides[size_t(i)] & sides[size_t(j)], curve);
      }
      return it->second;
    };
    const int n = int(F.size());
    for (int f = 0; f < n; ++f) {
      const Triangle t = F[size_t(f)];
      const std::array<int, 3> s = {side(t[0]), side(t[1]), side(t[2])};
      if (!((s[0] < 0 || s[1] < 0 || s[2] < 0) && (s[0] > 0 || s[1] > 0 || s[2] > 0))) continue;
      // Rotate so that corner 0 is the one on the curve (one vertex on it) or the one alone on
      // its side (none on it); rotation keeps the orientation.
      int first = 0;
      const int zeros = int(s[0] == 0) + int(s[1] == 0) + int(s[2] == 0);
      for (int k = 0; k < 3; ++k) {
        const bool on_curve = s[size_t(k)] == 0;
        const bool alone =
            s[size_t(k)] != s[size_t((k + 1) % 3)] && s[size_t(k)] != s[size_t((k + 2) % 3)];
        if (zeros == 1 ? on_curve : alone) first = k;
      }
      const int i0 = t[size_t(first)], i1 = t[size_t((first + 1) % 3)],
                i2 = t[size_t((first + 2) % 3)];
      if (zeros == 1) {
        const int p = crossing_vertex(i1, i2);
        if (p < 0) continue;
        set_triangle(f, {i0, i1, p});
        add_triangle({i0, p, i2});
        continue;
      }
      const int p = crossing_vertex(i0, i1), q = crossing_vertex(i0, i2);
      if (p < 0 && q < 0) continue;
      if (p < 0 || q < 0) {
        // The curve ends inside: split through the one crossing, so the mesh stays conforming.
        if (q < 0) {
          set_triangle(f, {i0, p, i2});
          add_triangle({p, i1, i2});
        } else {
          set_triangle(f, {i0, i1, q});
          add_triangle({q, i1, i2});
        }
        continue;
      }
      set_triangle(f, {i0, p, q});
      // The quad p, i1, i2, q: split along its shorter diagonal.
      if ((V[size_t(p)] - V[size_t(i2)]).squaredNorm() <=
          (V[size_t(i1)] - V[size_t(q)]).squaredNorm()) {
        add_triangle({p, i1, i2});
        add_triangle({p, i2, q});
      } else {
        add_triangle({p, i1, q});
        add_triangle({i1, i2, q});
      }
    }
  }
};

// A vertex at p (inside the mesh, else nothing): an existing one there, the nearest free vertex
// of the triangle holding p moved there, or a new one splitting that triangle (or its edge).
std::optional<int> vertex_at(Work& w, const Eigen::Vector2d& p, int curve) {
  for (int f = 0; f < int(w.F.size()); ++f) {
    const Triangle t = w.F[size_t(f)];
    std::array<double, 3> b;  // twice the areas opposite each vertex
    for (int k = 0; k < 3; ++k)
      b[size_t(k)] =
          cross(w.V[size_t(t[size_t((k + 2) % 3)])] - w.V[size_t(t[size_t((k + 1) % 3)])],
                p - w.V[size_t(t[size_t((k + 1) % 3)])]);
    const double tolerance = 1e-12 * w.area2(t);
    if (*std::min_element(b.begin(), b.end()) < -tolerance) continue;
    std::array<int, 3> by_distance = t;
    std::sort(by_distance.begin(), by_distance.end(), [&](int i, int j) {
      return (w.V[size_t(i)] - p).squaredNorm() < (w.V[size_t(j)] - p).squaredNorm();
    });
    if ((w.V[size_t(by_distance[0])] - p).norm() <= 1e-9 * std::max(1.0, p.norm()))
      return by_distance[0];
    for (int i : by_distance)
      if (w.try_move(i, p, curve)) return i;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(b[size_t(k)]) > tolerance) continue;
      const int a = t[size_t((k + 1) % 3)], c = t[size_t((k + 2) % 3)];
      const int m = w.add_vertex(p, w.sides[size_t(a)] & w.sides[size_t(c)], curve);
      w.split_edge(a, c, m);
      return m;
    }
    const int m = w.add_vertex(p, 0, curve);
    w.split_triangle(f, m);
    return m;
  }
  return std::nullopt;
}

// Makes the mesh follow the edge a -> b (pixels) of a polygon whose ends are mesh vertices.
void follow_edge(Work& w, int curve, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                 double snap) {
  const Eigen::Vector2d along = b - a;
  const double length = along.norm();
  const Eigen::Vector2d normal(-along.y() / length, along.x() / length);
  const Eigen::AlignedBox2d near(a.cwiseMin(b).array() - snap, a.cwiseMax(b).array() + snap);
  for (int i = 0; i < int(w.V.size()); ++i) {
    const Eigen::Vector2d& v = w.V[size_t(i)];
    if (w.locked[size_t(i)] || !near.contains(v) || !(std::abs(normal.dot(v - a)) < snap)) continue;
    const double u = (v - a).dot(along) / (length * length);
    if (u > 0 && u < 1) w.try_move(i, a + u * along, curve);
  }
  const double tolerance = w.on_curve;
  auto offset = [&](int v) { return normal.dot(w.V[size_t(v)] - a); };
  w.cut(
      curve,
      [&](int v) {
        const double d = offset(v);
        return d > tolerance ? 1 : d < -tolerance ? -1 : 0;
      },
      [&](int i, int j) -> std::optional<Eigen::Vector2d> {
        const double di = offset(i), dj = offset(j);
        const Eigen::Vector2d p =
            w.V[size_t(i)] + di / (di - dj) * (w.V[size_t(j)] - w.V[size_t(i)]);
        const double u = (p - a).dot(along) / (length * length);
        if (u < -1e-9 || u > 1 + 1e-9) return std::nullopt;
        return p;
      });
}

// Makes the mesh follow an implicit curve.
void follow_level(Work& w, int index, const MeshCurve& curve, double snap) {
  // The level is positive outside its bounds (here widened, so that points moved onto the
  // curve where it touches them are not taken for outside by rounding).
  const double reach = snap + 1e3 * w.on_curve;
  const Eigen::AlignedBox2d near(curve.bounds.min().array() - reach,
                                 curve.bounds.max().array() + reach);
  for (int i = 0; i < int(w.V.size()); ++i) {
    const Eigen::Vector2d& v = w.V[size_t(i)];
    if (w.locked[size_t(i)] || !near.contains(v) || !(std::abs(curve.level(v)) < snap)) continue;
    w.try_move(i, curve.project(v), index);
  }
  const double tolerance = w.on_curve;
  std::vector<int8_t> sides(w.V.size());
  for (size_t i = 0; i < w.V.size(); ++i) {
    const double f = near.contains(w.V[i]) ? curve.level(w.V[i]) : 1.0;
    sides[i] = int8_t(f > tolerance ? 1 : f < -tolerance ? -1 : 0);
  }
  w.cut(
      index, [&](int v) { return size_t(v) < sides.size() ? int(sides[size_t(v)]) : 0; },
      [&](int i, int j) -> std::optional<Eigen::Vector2d> {
        const Eigen::Vector2d a = w.V[size_t(i)], b = w.V[size_t(j)];
        auto along = [&](double t) { return curve.level(a + t * (b - a)); };
        return a + bracketed_root(along, 0.0, 1.0, 1e-12) * (b - a);
      });
}

// The largest angle a triangle spans at a polygon's corner (fan_out).
constexpr double kMaxApexAngle = std::numbers::pi / 6;

// Splits the triangles at every vertex of `apexes` until each spans at most 30 degrees there,
// by halving the edge opposite the apex (and so the triangle on its other side). A map with a
// cone at a polygon's corner (as the focus lens's start has: a point's shift grows with its
// distance from the corner) is averaged over each triangle at the corner; a triangle spanning
// 150 degrees there folds under the average where the map does not.
void fan_out(Work& w, const std::vector<int>& apexes) {
  for (int apex : apexes) {
    for (bool split = true; split;) {
      split = false;
      for (int f : w.around[size_t(apex)]) {
        const Triangle t = w.F[size_t(f)];
        int k = 0;
        while (t[size_t(k)] != apex) ++k;
        const int a = t[size_t((k + 1) % 3)], b = t[size_t((k + 2) % 3)];
        const Eigen::Vector2d& o = w.V[size_t(apex)];
        const Eigen::Vector2d ea = w.V[size_t(a)] - o, eb = w.V[size_t(b)] - o;
        if (std::atan2(cross(ea, eb), ea.dot(eb)) <= kMaxApexAngle) continue;
        // Where the angle's bisector meets a - b (it divides a - b as |ea| to |eb|), so each split
        // halves the angle: the midpoint of a - b, when the angle is near 180 degrees (a polygon's
        // nearly straight corner), lies next to the apex and leaves a near-straight angle beside
        // it, splitting on towards the apex in ever thinner slivers.
        const double la = ea.norm(), lb = eb.norm();
        const Eigen::Vector2d bisector = (lb * w.V[size_t(a)] + la * w.V[size_t(b)]) / (la + lb);
        w.split_edge(a, b, w.add_vertex(bisector, w.sides[size_t(a)] & w.sides[size_t(b)], -1));
        split = true;
        break;
      }
    }
  }
}

// Whether edge a - b runs along a curve (both ends placed on it and its midpoint near it), not
// across it as a chord.
bool along_curve(const Work& w, const std::vector<MeshCurve>& curves, int a, int b) {
  const int curve = w.curve_of[size_t(a)];
  return curve >= 0 && curve == w.curve_of[size_t(b)] &&
         std::abs(curves[size_t(curve)].level(0.5 * (w.V[size_t(a)] + w.V[size_t(b)]))) <
             0.1 * (w.V[size_t(a)] - w.V[size_t(b)]).norm();
}

// Flips, until none is left (at most kPasses rounds), every edge of a sliver (an angle below
// kSliver) inside the mesh where the flip makes its triangles fatter: the quad is convex, the
// Delaunay test fails (the angles opposite the edge sum to more than 180 degrees), and the
// smallest angle grows. Not an edge along a curve, nor one that would leave a triangle spanning
// more than fan_out's angle at a polygon's corner, nor one with a corner on the mesh's side
// (where a footprint's edge meets the image border, flips there left a 0.2 px^2 triangle whose
// shape distortion, 9.2, became the paragraph lens's largest; 2.3 without). Following curves,
// fanning out corners (a bisector point lies next to the apex where one of its edges is short)
// and refining leave slivers beside their splits, which a map that bends over them folds or
// interpolates badly. On a mask's outline (an ellipse with a bite, 89 corners 1 - 20 px apart)
// the focus lens fitted zoom 1.15 of 2 on mesh 100 and 2 on mesh 400 without flips, moved points
// by 1.3 px between the two at zoom 3 with flips kept off the corners, and 0.25 px with them.
void flip_slivers(Work& w, const std::vector<MeshCurve>& curves, const std::vector<int>& apexes) {
  constexpr int kPasses = 16;
  constexpr double kSliver = std::numbers::pi / 18;  // 10 degrees
  std::vector<char> apex(w.V.size(), 0);
  for (int v : apexes) apex[size_t(v)] = 1;
  auto angle = [&](int at, int p, int q) {
    const Eigen::Vector2d u = w.V[size_t(p)] - w.V[size_t(at)],
                          v = w.V[size_t(q)] - w.V[size_t(at)];
    return std::atan2(std::abs(cross(u, v)), u.dot(v));
  };
  // Whether triangle f is a sliver: the sine of its smallest angle (opposite its shortest edge),
  // twice its area over its two longer edges, below kSliver's. Cheap, so that only slivers are
  // looked at further.
  const double sin_sliver = std::sin(kSliver);
  auto sliver = [&](const Triangle& t) {
    const std::array<double, 3> l = w.edge_lengths(t);
    return std::abs(w.area2(t)) < sin_sliver * l[1] * l[2];
  };
  for (int pass = 0; pass < kPasses; ++pass) {
    int flips = 0;
    for (int f = 0; f < int(w.F.size()); ++f) {
      if (!sliver(w.F[size_t(f)])) continue;
      for (int k = 0; k < 3; ++k) {
        const Triangle t = w.F[size_t(f)];
        const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)], x = t[size_t((k + 2) % 3)];
        int g = -1, y = -1;
        for (int h : w.around[size_t(a)]) {
          const Triangle& u = w.F[size_t(h)];
          for (int j = 0; j < 3; ++j)
            if (u[size_t(j)] == b && u[size_t((j + 1) % 3)] == a) g = h, y = u[size_t((j + 2) % 3)];
        }
        if (g < 0 || angle(x, a, b) + angle(y, a, b) <= std::numbers::pi * (1 + 1e-9)) continue;
        // The quad a, y, b, x: its diagonal x - y, if both triangles keep the orientation (the
        // neighbour's, where f has none: x on a - b, a triangle of three points of a straight
        // curve, which the flip removes while keeping the curve's edges a - x and x - b).
        const Triangle first = {a, y, x}, second = {y, b, x};
        // (x within on_curve of a - b: three points of a curve placed 1.5e-10 px off a line,
        // whose sign the flattening then turned.)
        const bool flat =
            std::abs(w.area2(t)) <= w.on_curve * (w.V[size_t(a)] - w.V[size_t(b)]).norm();
        const double sign = flat ? w.area2(w.F[size_t(g)]) : w.area2(t);
        if (!(w.area2(first) * sign > 0 && w.area2(second) * sign > 0)) continue;
        auto smallest = [&](const Triangle& u) {
          return std::min(
              {angle(u[0], u[1], u[2]), angle(u[1], u[2], u[0]), angle(u[2], u[0], u[1])});
        };
        const double before = std::min(smallest(t), smallest(w.F[size_t(g)]));
        if (std::min(smallest(first), smallest(second)) <= before) continue;
        // (A flat f's flip spans at a and b what g spanned there: x is on a - b.)
        if (!flat && ((apex[size_t(a)] && angle(a, y, x) > kMaxApexAngle * (1 + 1e-9)) ||
                      (apex[size_t(b)] && angle(b, y, x) > kMaxApexAngle * (1 + 1e-9))))
          continue;
        if ((!flat && along_curve(w, curves, a, b)) || w.sides[size_t(a)] || w.sides[size_t(b)] ||
            w.sides[size_t(x)] || w.sides[size_t(y)])
          continue;
        w.set_triangle(f, first);
        w.set_triangle(g, second);
        ++flips;
        break;
      }
    }
    if (flips == 0) return;
  }
}

// The longest edge of triangle f, as its first corner k (the edge t[k] -> t[k + 1]).
int longest_edge(const Work& w, int f) {
  const Triangle& t = w.F[size_t(f)];
  int longest = 0;
  double best = 0;
  for (int k = 0; k < 3; ++k) {
    const double l =
        (w.V[size_t(t[size_t((k + 1) % 3)])] - w.V[size_t(t[size_t(k)])]).squaredNorm();
    if (l > best) best = l, longest = k;
  }
  return longest;
}

// Splits triangle f at the midpoint of its longest edge a - b, and the triangle across it; that
// one's longest edge first, as long as it is another (longest-edge propagation, Rivara 1984).
// A midpoint of an edge along a curve (not a chord across it) goes onto the curve.
void split_longest(Work& w, const std::vector<MeshCurve>& curves, int f) {
  for (;;) {
    const Triangle& t = w.F[size_t(f)];
    const int k = longest_edge(w, f);
    const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
    int across = -1;
    for (int g : w.around[size_t(a)]) {
      const Triangle& u = w.F[size_t(g)];
      if (g != f && std::find(u.begin(), u.end(), b) != u.end()) across = g;
    }
    if (across >= 0) {
      const Triangle& u = w.F[size_t(across)];
      const int j = longest_edge(w, across);
      const int c = u[size_t(j)], d = u[size_t((j + 1) % 3)];
      if (!((c == a && d == b) || (c == b && d == a))) {
        split_longest(w, curves, across);
        continue;  // f is unchanged; the triangle across a - b is new
      }
    }
    const Eigen::Vector2d middle = 0.5 * (w.V[size_t(a)] + w.V[size_t(b)]);
    Eigen::Vector2d m = middle;
    const int curve = w.curve_of[size_t(a)];
    bool along = along_curve(w, curves, a, b);
    if (along) {
      m = curves[size_t(curve)].project(middle);
      // Unless a triangle of the edge would fold there (a curve bending more than the mesh).
      for (int g : w.around[size_t(a)]) {
        const Triangle& u = w.F[size_t(g)];
        for (int j = 0; j < 3; ++j) {
          const int p = u[size_t(j)], q = u[size_t((j + 1) % 3)], x = u[size_t((j + 2) % 3)];
          if (!((p == a && q == b) || (p == b && q == a))) continue;
          const Eigen::Vector2d &vp = w.V[size_t(p)], &vq = w.V[size_t(q)], &vx = w.V[size_t(x)];
          if (!(cross(m - vp, vx - vp) > 0 && cross(vq - m, vx - m) > 0)) along = false;
        }
      }
      if (!along) m = middle;
    }
    w.split_edge(a, b,
                 w.add_vertex(m, w.sides[size_t(a)] & w.sides[size_t(b)], along ? curve : -1));
    return;
  }
}

// Adds to `bent` the triangles of `dirty` with a corner on a `slope` curve whose slope is off by
// more than refine.slope_tolerance of their smaller singular value (`image`: the map at every
// vertex). For a map quadratic across a triangle, the gradient of its linear interpolant at the
// centroid is off by 4/3 sum_k d_k grad(l_k), d_k the map's deviation at the midpoint of the
// edge opposite corner k and |grad l_k| = 1 / h_k, its height there: a triangle with an obtuse
// corner has a small height, so a bend its positions hardly show is a large error of its shape.
// Following a curve makes such triangles; away from the curves the grid's are right-angled, and
// a kink of the map along a line no curve follows would be split all along it to no end.
void add_sloped_off(const Work& w, const std::vector<MeshCurve>& curves,
                    const MeshRefinement& refine, const Eigen::MatrixX2d& image,
                    const std::vector<int>& dirty, std::vector<int>& bent) {
  std::vector<int> near;
  for (int f : dirty) {
    const Triangle& t = w.F[size_t(f)];
    if (w.area2(t) > 0 && std::any_of(t.begin(), t.end(), [&](int v) {
          const int curve = w.curve_of[size_t(v)];
          return curve >= 0 && curves[size_t(curve)].slope;
        }))
      near.push_back(f);
  }
  Eigen::MatrixX2d midpoints(3 * Eigen::Index(near.size()), 2);  // opposite each corner
  for (size_t i = 0; i < near.size(); ++i) {
    const Triangle& t = w.F[size_t(near[i])];
    for (size_t k = 0; k < 3; ++k)
      midpoints.row(3 * Eigen::Index(i) + Eigen::Index(k)) =
          0.5 * (w.V[size_t(t[(k + 1) % 3])] + w.V[size_t(t[(k + 2) % 3])]).transpose();
  }
  const Eigen::MatrixX2d mapped = refine.map(midpoints);
  for (size_t i = 0; i < near.size(); ++i) {
    const Triangle& t = w.F[size_t(near[i])];
    double error = 0;
    for (size_t k = 0; k < 3; ++k) {
      const int a = t[(k + 1) % 3], b = t[(k + 2) % 3];
      const Eigen::RowVector2d deviation =
          mapped.row(3 * Eigen::Index(i) + Eigen::Index(k)) - 0.5 * (image.row(a) + image.row(b));
      error += deviation.norm() * (w.V[size_t(b)] - w.V[size_t(a)]).norm();
    }
    error *= 4.0 / 3 / w.area2(t);
    Eigen::Matrix2d source, target;
    source << w.V[size_t(t[1])] - w.V[size_t(t[0])], w.V[size_t(t[2])] - w.V[size_t(t[0])];
    target.col(0) = (image.row(t[1]) - image.row(t[0])).transpose();
    target.col(1) = (image.row(t[2]) - image.row(t[0])).transpose();
    const double smaller = std::abs(signed_singular_values(target * source.inverse())(1));
    if (error > refine.slope_tolerance * smaller) bent.push_back(near[i]);
  }
}

// Splits triangles where `refine.map` bends between the ends of an edge (see conform_mesh). A
// pass looks at the edges of the triangles the previous one made (the first at all).
void refine_where_bent(Work& w, const std::vector<MeshCurve>& curves,
                       const MeshRefinement& refine) {
  Eigen::MatrixX2d image(0, 2);  // the map at each vertex, filled as vertices are added
  std::vector<int> dirty(w.F.size());
  for (size_t f = 0; f < dirty.size(); ++f) dirty[f] = int(f);
  for (int pass = 0; pass < refine.max_passes && !dirty.empty(); ++pass) {
    const Eigen::Index done = image.rows(), n = Eigen::Index(w.V.size());
    Eigen::MatrixX2d points(n - done, 2);
    for (Eigen::Index i = done; i < n; ++i) points.row(i - done) = w.V[size_t(i)].transpose();
    image.conservativeResize(n, 2);
    image.bottomRows(n - done) = refine.map(points);
    // The edges to look at, once each (an edge inside the mesh is in two triangles, once each
    // way round: it is taken from the one that has it as a -> b, a < b; an edge on a side of the
    // mesh, ends on one side, is in one triangle, and taken from it), and the map at their
    // midpoints. (Not even an edge whose ends the map leaves in place is skipped: a curve where
    // the map turns may pass between them.)
    std::vector<std::pair<int, int>> edges;
    for (int f : dirty) {
      const Triangle& t = w.F[size_t(f)];
      for (int k = 0; k < 3; ++k) {
        const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
        if (a < b || (w.sides[size_t(a)] & w.sides[size_t(b)]) != 0)
          edges.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
    Eigen::MatrixX2d midpoints(Eigen::Index(edges.size()), 2);
    for (size_t e = 0; e < edges.size(); ++e)
      midpoints.row(Eigen::Index(e)) =
          0.5 * (w.V[size_t(edges[e].first)] + w.V[size_t(edges[e].second)]).transpose();
    const Eigen::MatrixX2d mapped = refine.map(midpoints);
    std::vector<int> bent;
    for (size_t e = 0; e < edges.size(); ++e) {
      const auto [a, b] = edges[e];
      const Eigen::RowVector2d mean = 0.5 * (image.row(a) + image.row(b));
      if (!((mapped.row(Eigen::Index(e)) - mean).norm() > refine.tolerance)) continue;
      for (int f : w.around[size_t(a)]) {
        const Triangle& t = w.F[size_t(f)];
        if (std::find(t.begin(), t.end(), b) != t.end()) bent.push_back(f);
      }
    }
    if (refine.slope_tolerance > 0) add_sloped_off(w, curves, refine, image, dirty, bent);
    // and where it bends inside a triangle (its edges may be straight where a curve of the map,
    // such as a footprint's edge rounded at an image corner, passes by).
    Eigen::MatrixX2d centroids(Eigen::Index(dirty.size()), 2);
    for (size_t k = 0; k < dirty.size(); ++k) {
      const Triangle& t = w.F[size_t(dirty[k])];
      centroids.row(Eigen::Index(k)) =
          ((w.V[size_t(t[0])] + w.V[size_t(t[1])] + w.V[size_t(t[2])]) / 3).transpose();
    }
    const Eigen::MatrixX2d inside = refine.map(centroids);
    for (size_t k = 0; k < dirty.size(); ++k) {
      const Triangle& t = w.F[size_t(dirty[k])];
      const Eigen::RowVector2d mean = (image.row(t[0]) + image.row(t[1]) + image.row(t[2])) / 3;
      if ((inside.row(Eigen::Index(k)) - mean).norm() > refine.tolerance) bent.push_back(dirty[k]);
    }
    std::sort(bent.begin(), bent.end());
    bent.erase(std::unique(bent.begin(), bent.end()), bent.end());
    // Each bent triangle that this pass has not changed yet is split at the midpoint of its
    // longest edge, with the triangle across it, whose longest edge is split first where it is
    // another (Rivara's longest-edge propagation), so that no split makes a thin triangle.
    w.touched.assign(w.F.size(), 0);
    for (int f : bent)
      if (!w.touched[size_t(f)]) split_longest(w, curves, f);
    dirty.clear();
    for (size_t f = 0; f < w.F.size(); ++f)
      if (w.touched[f]) dirty.push_back(int(f));
    w.touched.clear();
  }
}

// Merges the vertices that an edge joins nearer than on_curve (two curves crossing within it of
// each other, or a crossing that near a vertex already on another curve) into the older, and
// drops the triangles between them: they were a millionth of a cell across, and a measure of
// the warp read them as flipped. A merge that would turn a triangle left between other vertices,
// or join a vertex on a side to one that is not on it, is not made. The older is kept, so the
// input's vertices keep their indices.
void merge_coincident(Work& w) {
  std::vector<int> into(w.V.size());
  std::iota(into.begin(), into.end(), 0);
  // Of each root, the vertices merged into it, as a list through `next` from the root to `last`
  // (a vector a vertex was a heap block each: 3 % of a circle's first placement).
  std::vector<int> next(w.V.size(), -1), last(w.V.size());
  std::iota(last.begin(), last.end(), 0);
  auto root = [&](int v) {
    while (into[size_t(v)] != v) v = into[size_t(v)];
    return v;
  };
  const double within = w.on_curve * w.on_curve;
  auto coincident = [&](int a, int b) {
    return (w.V[size_t(a)] - w.V[size_t(b)]).squaredNorm() <= within;
  };
  // Whether merging root b into root a keeps every triangle at b that is left counter-clockwise
  // and not flat (its height over its longest edge above 1e-9: a merge near a side once left
  // three vertices 1e-5 px from it, none on it, as a triangle 1.3 px long of 1e-14 px^2, which
  // the warp's measure read as flipped). A triangle left with two coincident corners is dropped by
  // their merge in turn (the refinement once split three edges at one point: the first merge of
  // the three was refused for the triangle the third made flat, and the mesh kept all three).
  auto keeps_orientation = [&](int a, int b) {
    for (int m = b; m >= 0; m = next[size_t(m)])
      for (int f : w.around[size_t(m)]) {
        Triangle u;
        for (size_t k = 0; k < 3; ++k) {
          const int r = root(w.F[size_t(f)][k]);
          u[k] = r == b ? a : r;
        }
        if (coincident(u[0], u[1]) || coincident(u[1], u[2]) || coincident(u[2], u[0]))
          continue;  // dropped
        const double longest = w.edge_lengths(u)[2];
        if (!(w.area2(u) > 1e-9 * longest * longest)) return false;
      }
    return true;
  };
  bool merged = false;
  for (const Triangle& t : w.F)
    for (size_t k = 0; k < 3; ++k) {
      int a = root(t[k]), b = root(t[(k + 1) % 3]);
      if (a == b || w.sides[size_t(a)] != w.sides[size_t(b)] || !coincident(a, b)) continue;
      if (a > b) std::swap(a, b);
      if (!keeps_orientation(a, b)) continue;
      into[size_t(b)] = a;
      next[size_t(last[size_t(a)])] = b;
      last[size_t(a)] = last[size_t(b)];
      if (w.curve_of[size_t(a)] < 0) w.curve_of[size_t(a)] = w.curve_of[size_t(b)];
      merged = true;
    }
  if (!merged) return;
  std::vector<int> index(w.V.size(), -1);
  size_t kept = 0;
  for (size_t v = 0; v < w.V.size(); ++v) {
    if (root(int(v)) != int(v)) continue;
    index[v] = int(kept);
    w.V[kept] = w.V[v];
    w.sides[kept] = w.sides[v];
    w.curve_of[kept] = w.curve_of[v];
    ++kept;
  }
  w.V.resize(kept);
  w.sides.resize(kept);
  w.curve_of.resize(kept);
  std::vector<Triangle> faces;
  for (const Triangle& t : w.F) {
    const Triangle u = {index[size_t(root(t[0]))], index[size_t(root(t[1]))],
                        index[size_t(root(t[2]))]};
    if (u[0] != u[1] && u[1] != u[2] && u[2] != u[0]) faces.push_back(u);
  }
  w.F = std::move(faces);
}

}  // namespace

MeshCurve circle_curve(const Eigen::Vector2d& center, double radius) {
  require(center.allFinite() && std::isfinite(radius) && radius > 0, "circle_curve",
          "centre must be finite and radius > 0, got " + std::to_string(radius));
  MeshCurve c;
  c.level = [center, radius](const Eigen::Vector2d& p) { return (p - center).norm() - radius; };
  c.project = [center, radius](const Eigen::Vector2d& p) {
    const Eigen::Vector2d offset = p - center;
    const double distance = offset.norm();
    return distance > 0 ? Eigen::Vector2d(center + offset * (radius / distance))
                        : Eigen::Vector2d(center + Eigen::Vector2d(radius, 0));
  };
  c.bounds = Eigen::AlignedBox2d(center.array() - radius, center.array() + radius);
  return c;
}

MeshCurve polygon_curve(const std::vector<Eigen::Vector2d>& vertices) {
  validate_polygon(vertices, "polygon_curve");
  // The nearest point of the boundary to p, and whether p is inside (the crossing rule).
  auto nearest = [vertices](const Eigen::Vector2d& p, bool& inside) {
    inside = false;
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector2d point = vertices[0];
    for (size_t k = 0, j = vertices.size() - 1; k < vertices.size(); j = k++) {
      const Eigen::Vector2d &a = vertices[j], &b = vertices[k];
      if ((a.y() > p.y()) != (b.y() > p.y()) &&
          p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
        inside = !inside;
      const Eigen::Vector2d d = b - a;
      const Eigen::Vector2d q = a + std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) * d;
      if ((p - q).squaredNorm() < best) best = (p - q).squaredNorm(), point = q;
    }
    return point;
  };
  MeshCurve c;
  c.polygon = vertices;
  c.level = [nearest](const Eigen::Vector2d& p) {
    bool inside;
    const double d = (nearest(p, inside) - p).norm();
    return inside ? -d : d;
  };
  c.project = [nearest](const Eigen::Vector2d& p) {
    bool inside;
    return nearest(p, inside);
  };
  for (const Eigen::Vector2d& v : vertices) c.bounds.extend(v);
  return c;
}

PlanarMesh conform_mesh(const PlanarMesh& mesh, const std::vector<MeshCurve>& curves, double snap,
                        const MeshRefinement& refine, std::vector<int>* on_curve) {
  require(std::isfinite(snap) && snap >= 0, "conform_mesh",
          "snap distance must be finite and >= 0, got " + std::to_string(snap));
  require(!refine.map ||
              (std::isfinite(refine.tolerance) && refine.tolerance > 0 && refine.max_passes >= 0 &&
               std::isfinite(refine.slope_tolerance) && refine.slope_tolerance >= 0),
          "conform_mesh",
          "refinement needs a tolerance > 0, a slope tolerance >= 0 and max_passes >= 0");
  for (const MeshCurve& curve : curves)
    require(curve.level && curve.project, "conform_mesh",
            "every curve needs a level and a projection");
  Work w;
  w.V.resize(size_t(mesh.V.rows()));
  for (size_t i = 0; i < w.V.size(); ++i) w.V[i] = mesh.V.row(Eigen::Index(i)).transpose();
  w.around.resize(w.V.size());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    w.add_triangle({mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)});
  double area = 0;
  for (const Triangle& t : w.F) area += 0.5 * std::abs(w.area2(t));
  w.on_curve = 1e-6 * std::sqrt(2 * area / double(std::max<size_t>(w.F.size(), 1)));
  w.sides = mesh.sides;
  w.box = Eigen::AlignedBox2d(mesh.V.colwise().minCoeff().transpose(),
                              mesh.V.colwise().maxCoeff().transpose());
  w.locked.resize(w.V.size());
  for (size_t i = 0; i < w.V.size(); ++i) w.locked[i] = w.sides[i] != 0;
  w.curve_of.assign(w.V.size(), -1);
  std::vector<int> corners;
  for (int c = 0; c < int(curves.size()); ++c) {
    const MeshCurve& curve = curves[size_t(c)];
    if (curve.polygon.empty()) {
      follow_level(w, c, curve, snap);
      continue;
    }
    for (const Eigen::Vector2d& p : curve.polygon)
      if (const std::optional<int> v = vertex_at(w, p, c)) corners.push_back(*v);
    const size_t n = curve.polygon.size();
    for (size_t k = 0; k < n; ++k)
      follow_edge(w, c, curve.polygon[k], curve.polygon[(k + 1) % n], snap);
  }
  fan_out(w, corners);
  if (refine.map) refine_where_bent(w, curves, refine);
  flip_slivers(w, curves, corners);
  merge_coincident(w);
  PlanarMesh out;
  out.V.resize(Eigen::Index(w.V.size()), 2);
  for (size_t i = 0; i < w.V.size(); ++i) out.V.row(Eigen::Index(i)) = w.V[i].transpose();
  out.F.resize(Eigen::Index(w.F.size()), 3);
  for (size_t f = 0; f < w.F.size(); ++f)
    out.F.row(Eigen::Index(f)) << w.F[f][0], w.F[f][1], w.F[f][2];
  out.sides = std::move(w.sides);
  if (on_curve) *on_curve = std::move(w.curve_of);
  return out;
}

}  // namespace geolens
