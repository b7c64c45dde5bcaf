#pragma once
// Test support: geometries of the vector-data tests.

#include <utility>
#include <vector>

#include "geolens/io/vector_data.h"

namespace geolens::test {

/// A geometry of `type` with `paths` (each #P x 2, pixels) and `rings` (per polygon of a
/// MultiPolygon, its number of paths).
inline Geometry make_geometry(GeometryType type, std::vector<Eigen::MatrixX2d> paths,
                              std::vector<int> rings = {}) {
  Geometry g;
  g.type = type;
  g.paths = std::move(paths);
  g.rings = std::move(rings);
  return g;
}

}  // namespace geolens::test
