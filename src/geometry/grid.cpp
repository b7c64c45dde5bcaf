#include "geolens/geometry/grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "geolens/core/errors.h"

namespace geolens {

Grid make_grid(double width, double height, int vertices_long_side) {
  require(
      std::isfinite(width) && std::isfinite(height) && width > 0 && height > 0, "make_grid",
      "image size must be positive, got " + std::to_string(width) + " x " + std::to_string(height));
  require(vertices_long_side >= 2, "make_grid",
          "need at least 2 vertices per side, got " + std::to_string(vertices_long_side));
  const double long_side = std::max(width, height);
  const double step = long_side / (vertices_long_side - 1);
  auto count = [&](double side) { return std::max(2, int(std::lround(side / step)) + 1); };
  Grid g;
  g.columns = width >= height ? vertices_long_side : count(width);
  g.rows = width >= height ? count(height) : vertices_long_side;
  const double dx = width / (g.columns - 1), dy = height / (g.rows - 1);
  g.cell = 0.5 * (dx + dy);
  g.V.resize(g.columns * g.rows, 2);
  g.sides.assign(size_t(g.columns) * g.rows, 0);
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.columns; ++c) {
      const int i = r * g.columns + c;
      g.V(i, 0) = c == g.columns - 1 ? width : c * dx;
      g.V(i, 1) = r == g.rows - 1 ? height : r * dy;
      g.sides[size_t(i)] = (c == 0 ? kLeft : 0) | (c == g.columns - 1 ? kRight : 0) |
                           (r == 0 ? kTop : 0) | (r == g.rows - 1 ? kBottom : 0);
    }
  }
  g.F.resize(2 * (g.columns - 1) * (g.rows - 1), 3);
  int t = 0;
  for (int r = 0; r + 1 < g.rows; ++r) {
    for (int c = 0; c + 1 < g.columns; ++c) {
      const int a = r * g.columns + c, b = a + 1, d = a + g.columns, e = d + 1;
      // With y down, (b - a) x (c - a) > 0 means a -> b -> c turns clockwise on screen.
      if ((r + c) % 2 == 0) {  // diagonal a-e
        g.F.row(t++) << a, b, e;
        g.F.row(t++) << a, e, d;
      } else {  // diagonal b-d
        g.F.row(t++) << a, b, d;
        g.F.row(t++) << b, e, d;
      }
    }
  }
  return g;
}

void require_mesh_vertices(int vertices_long_side, const char* function, const char* option) {
  require_option(vertices_long_side >= kMinMeshVertices && vertices_long_side <= kMaxMeshVertices,
                 function, option,
                 "must be in [" + std::to_string(kMinMeshVertices) + ", " +
                     std::to_string(kMaxMeshVertices) + "] vertices per side, got " +
                     std::to_string(vertices_long_side));
}

}  // namespace geolens
