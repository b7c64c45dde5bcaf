#include "geolens/io/vector_data.h"

#include <numeric>

namespace geolens {

namespace {

// What is wrong with one path: a non-finite row, too few rows, a ring left open.
std::string path_problem(const Eigen::MatrixX2d& path, Eigen::Index min_rows, bool ring) {
  for (Eigen::Index i = 0; i < path.rows(); ++i)
    if (!path.row(i).allFinite()) return "row " + std::to_string(i) + " is not finite";
  if (path.rows() < min_rows)
    return "has " + std::to_string(path.rows()) + " positions, needs at least " +
           std::to_string(min_rows);
  if (ring && path.row(0) != path.row(path.rows() - 1))
    return "is not closed (its last position differs from its first)";
  return "";
}

// The first problem of the paths [first, first + count), each needing min_rows, or "" (named
// `what` and their index from `first`).
std::string paths_problem(const Geometry& g, size_t first, size_t count, Eigen::Index min_rows,
                          bool ring, const char* what) {
  for (size_t k = first; k < first + count; ++k) {
    const std::string problem = path_problem(g.paths[k], min_rows, ring);
    if (!problem.empty())
      return std::string(what) + " " + std::to_string(k - first) + " " + problem;
  }
  return "";
}

}  // namespace

std::string to_string(GeometryType type) {
  switch (type) {
    case GeometryType::kPoint:
      return "Point";
    case GeometryType::kMultiPoint:
      return "MultiPoint";
    case GeometryType::kLineString:
      return "LineString";
    case GeometryType::kMultiLineString:
      return "MultiLineString";
    case GeometryType::kPolygon:
      return "Polygon";
    case GeometryType::kMultiPolygon:
      return "MultiPolygon";
    case GeometryType::kGeometryCollection:
      return "GeometryCollection";
  }
  return "unknown";
}

std::string geometry_problem(const Geometry& g) {
  const std::string type = to_string(g.type);
  const size_t n = g.paths.size();
  if (g.type != GeometryType::kMultiPolygon && !g.rings.empty())
    return type + ": has ring counts, which only a MultiPolygon has";
  if (g.type != GeometryType::kGeometryCollection && !g.members.empty())
    return type + ": has members, which only a GeometryCollection has";
  std::string problem;
  switch (g.type) {
    case GeometryType::kPoint:
      if (n != 1 || g.paths[0].rows() != 1) return type + ": needs one path of one position";
      return paths_problem(g, 0, 1, 1, false, "Point: path");
    case GeometryType::kMultiPoint:
      if (n != 1) return type + ": has " + std::to_string(n) + " paths, needs 1";
      return paths_problem(g, 0, 1, 0, false, "MultiPoint: path");
    case GeometryType::kLineString:
      if (n != 1) return type + ": has " + std::to_string(n) + " paths, needs 1";
      return paths_problem(g, 0, 1, 2, false, "LineString: path");
    case GeometryType::kMultiLineString:
      return paths_problem(g, 0, n, 2, false, "MultiLineString: line");
    case GeometryType::kPolygon:
      return paths_problem(g, 0, n, 4, true, "Polygon: ring");
    case GeometryType::kMultiPolygon: {
      size_t first = 0;
      for (size_t p = 0; p < g.rings.size(); ++p) {
        if (g.rings[p] < 1)
          return type + ": polygon " + std::to_string(p) + " has " + std::to_string(g.rings[p]) +
                 " rings, needs at least 1";
        if (first + size_t(g.rings[p]) > n) break;
        problem = paths_problem(g, first, size_t(g.rings[p]), 4, true, "ring");
        if (!problem.empty()) return type + ": polygon " + std::to_string(p) + ": " + problem;
        first += size_t(g.rings[p]);
      }
      const long total = std::accumulate(g.rings.begin(), g.rings.end(), 0L);
      if (total != long(n))
        return type + ": its ring counts sum to " + std::to_string(total) + " but it has " +
               std::to_string(n) + " paths";
      return "";
    }
    case GeometryType::kGeometryCollection:
      if (n > 0) return type + ": has paths, which only its members have";
      for (size_t k = 0; k < g.members.size(); ++k) {
        problem = geometry_problem(g.members[k]);
        if (!problem.empty()) return type + ": member " + std::to_string(k) + ": " + problem;
      }
      return "";
  }
  return "unknown geometry type";
}

std::string vector_data_problem(const VectorData& data) {
  if (data.root != GeoJsonRoot::kFeatureCollection && data.features.size() != 1)
    return "a single feature or geometry holds " + std::to_string(data.features.size()) +
           " features";
  for (size_t k = 0; k < data.features.size(); ++k) {
    const Feature& f = data.features[k];
    if (!f.geometry) continue;
    const std::string problem = geometry_problem(*f.geometry);
    if (!problem.empty()) return "feature " + std::to_string(k) + ": " + problem;
  }
  return "";
}

}  // namespace geolens
