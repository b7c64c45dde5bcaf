#include "render/rasterize.h"

#include <cmath>

namespace geolens {

namespace {

struct Point {
  double x, y;
};

/// Where segment ab crosses the line coordinate `axis` = `value`. Computed from the endpoints in
/// a fixed order, so the two triangles sharing an edge get the same point.
Point crossing(Point a, Point b, int axis, double value) {
  if (b.x < a.x || (b.x == a.x && b.y < a.y)) std::swap(a, b);
  const double a_along = axis == 0 ? a.x : a.y, b_along = axis == 0 ? b.x : b.y;
  const double s = (value - a_along) / (b_along - a_along);
  Point p{a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)};
  (axis == 0 ? p.x : p.y) = value;
  return p;
}

}  // namespace

int clip_to_guard(const double (&x)[3], const double (&y)[3], double (&xs)[6][3],
                  double (&ys)[6][3]) {
  bool inside = true;
  for (int i = 0; i < 3; ++i)
    inside = inside && std::abs(x[i]) <= kGuard && std::abs(y[i]) <= kGuard;
  if (inside) {
    std::copy(x, x + 3, xs[0]);
    std::copy(y, y + 3, ys[0]);
    return 1;
  }
  // Sutherland-Hodgman against x >= -G, x <= G, y >= -G, y <= G: at most 7 vertices.
  Point polygon[8], clipped[8];
  int n = 3;
  for (int i = 0; i < 3; ++i) polygon[i] = {x[i], y[i]};
  for (int plane = 0; plane < 4 && n > 0; ++plane) {
    const int axis = plane / 2;
    const double side = plane % 2 == 0 ? -1 : 1;  // keep side * coordinate <= kGuard
    auto keep = [&](Point p) { return side * (axis == 0 ? p.x : p.y) <= kGuard; };
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const Point a = polygon[i], b = polygon[(i + 1) % n];
      if (keep(a)) clipped[m++] = a;
      if (keep(a) != keep(b)) clipped[m++] = crossing(a, b, axis, side * kGuard);
    }
    std::copy(clipped, clipped + m, polygon);
    n = m;
  }
  int count = 0;
  for (int i = 1; i + 1 < n; ++i, ++count) {
    xs[count][0] = polygon[0].x, xs[count][1] = polygon[i].x, xs[count][2] = polygon[i + 1].x;
    ys[count][0] = polygon[0].y, ys[count][1] = polygon[i].y, ys[count][2] = polygon[i + 1].y;
  }
  return count;
}

}  // namespace geolens
