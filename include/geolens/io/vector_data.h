#pragma once
// Vector data in pixels: the geometries, features and point tables that geojson.h and
// point_csv.h read and write and that warp/map_features.h maps through a lens.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace geolens {

/// The geometry types of GeoJSON (RFC 7946, section 3.1).
enum class GeometryType {
  kPoint,
  kMultiPoint,
  kLineString,
  kMultiLineString,
  kPolygon,
  kMultiPolygon,
  kGeometryCollection,
};

/// "Point", "MultiPoint", "LineString", "MultiLineString", "Polygon", "MultiPolygon",
/// "GeometryCollection": the GeoJSON type names.
std::string to_string(GeometryType type);

/// A GeoJSON geometry whose coordinates are pixels (x right, y down, origin top-left: source
/// pixels before a forward map, screen pixels after it), not longitude and latitude.
struct Geometry {
  GeometryType type = GeometryType::kPoint;  ///< which of the shapes below `paths` holds
  /// The coordinates, each path #P x 2 pixels:
  /// - Point: one path of one row;
  /// - MultiPoint: one path, one row per point (none for an empty MultiPoint);
  /// - LineString: one path of >= 2 rows; MultiLineString: one such path per line;
  /// - Polygon: one path per ring, the exterior ring first, then its holes; a ring is closed (its
  ///   last row equals its first) and has >= 4 rows;
  /// - MultiPolygon: the rings of every polygon, polygon after polygon (`rings` says how many
  ///   each has);
  /// - GeometryCollection: none.
  std::vector<Eigen::MatrixX2d> paths;
  /// MultiPolygon: the number of rings of each polygon, >= 1 each, summing to paths.size().
  /// Empty for every other type.
  std::vector<int> rings;
  /// GeometryCollection: its geometries. Empty for every other type.
  std::vector<Geometry> members;
};

/// What is wrong with `geometry` against the shapes documented at Geometry, in words (the first
/// problem found, naming the path, row or member), or "" if nothing: every coordinate must be
/// finite.
std::string geometry_problem(const Geometry& geometry);

/// A GeoJSON Feature (RFC 7946, section 3.2). Its id and properties are kept as JSON text, so they
/// pass through reading, mapping and writing unchanged (objects keep their key order).
struct Feature {
  std::optional<Geometry> geometry;  ///< empty for "geometry": null
  std::string id;                    ///< the "id" member as JSON text; "" when there is none
  std::string properties = "null";   ///< the "properties" member as JSON text: an object or null
};

/// The top-level object of a GeoJSON document, so it is written back as it was read.
enum class GeoJsonRoot {
  kFeatureCollection,
  kFeature,   ///< one feature: `features` has exactly one
  kGeometry,  ///< a bare geometry: one feature, without id or properties
};

/// A GeoJSON document as features.
struct VectorData {
  GeoJsonRoot root = GeoJsonRoot::kFeatureCollection;  ///< the object it was read from
  std::vector<Feature> features;  ///< in document order; one for a kFeature or kGeometry root
};

/// What is wrong with `data` ("" if nothing): the first feature whose geometry has a
/// geometry_problem, named by its index, or a kFeature or kGeometry root without exactly one
/// feature.
std::string vector_data_problem(const VectorData& data);

/// Points from a CSV file (point_csv.h), one per data line, with whatever followed x and y on
/// their line, so the rows of the file can be written back after some are dropped.
struct PointTable {
  std::string header;             ///< the header line, without its line break; "" for none
  Eigen::MatrixX2d points;        ///< #P x 2, pixels, finite
  std::vector<std::string> rest;  ///< #P: the text after "x,y" on each line (",id,..." or "")
};

}  // namespace geolens
