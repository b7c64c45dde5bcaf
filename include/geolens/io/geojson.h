#pragma once
// GeoJSON files (RFC 7946) of vector data in pixels: read, written back, and the properties of a
// feature looked up.

#include <cstddef>
#include <optional>
#include <string>

#include "geolens/io/vector_data.h"

namespace geolens {

/// The most positions a GeoJSON text holds by default: 2^22 (4 194 304), as many as the vertices
/// a map's features are densified to (warp/densify.h) and the points of a CSV table
/// (kMaxCsvPoints); the readers take another limit (--max-points).
inline constexpr size_t kMaxGeoJsonPoints = size_t(1) << 22;
/// The largest GeoJSON text read with the default limit, bytes: 64 MiB (a file of 63 MB of lines
/// took 0.6 GB and 3.7 s through `geolens map`; one of 100 MB 1.6-1.9 GB, a vector map of 500 MB
/// 3.2 GB).
inline constexpr size_t kMaxGeoJsonBytes = size_t(64) << 20;
/// The largest GeoJSON text read with a limit of `max_points` positions: kMaxGeoJsonBytes, or 16
/// bytes a position where the limit is raised beyond kMaxGeoJsonPoints.
size_t geojson_bytes_limit(size_t max_points);

/// Parses a GeoJSON document: a FeatureCollection, a Feature or a bare geometry (Point,
/// MultiPoint, LineString, MultiLineString, Polygon, MultiPolygon, GeometryCollection). Its
/// coordinates are taken as pixels (x right, y down; no coordinate reference system is applied),
/// each position exactly two numbers (an altitude is refused, not dropped). A feature's "id" and
/// "properties" are kept as JSON text, key order included; "bbox" and any other member are
/// ignored (a bbox would be stale once the coordinates are mapped).
/// @param name  where the text came from (a file name, "standard input"), for messages
/// Throws InvalidInput("parse_geojson: '<name>': <where>: <what>") for text that is not JSON
/// (with its line and column) or is nested deeper than kMaxJsonDepth, an unknown or missing "type",
/// a member of the wrong kind, a position that is not two finite numbers, or a geometry_problem
/// (vector_data.h); `<where>` names the feature by its index and the coordinate by its indices
/// ("feature 3: LineString coordinates[2]"); for more than `max_points` positions in all (>= 1;
/// kMaxGeoJsonPoints), and for text longer than geojson_bytes_limit(max_points).
VectorData parse_geojson(const std::string& text, const std::string& name,
                         size_t max_points = kMaxGeoJsonPoints);

/// The deepest nesting of arrays and objects in the JSON text `text` (0 for a scalar), counted
/// without parsing it, in one pass that does not recurse. The JSON readers (parse_geojson,
/// parse_map_style) refuse text nested deeper than kMaxJsonDepth before parsing it: their
/// readers recurse (a GeoJSON of 100 000 nested GeometryCollections overflowed the stack).
size_t json_depth(const std::string& text);
/// The deepest nesting of arrays and objects the JSON readers accept (json_depth).
inline constexpr size_t kMaxJsonDepth = 256;

/// parse_geojson of the file at `path`. Throws InvalidInput naming the path if it cannot be read
/// or holds more than geojson_bytes_limit(max_points) bytes (refused before it is read).
VectorData read_geojson(const std::string& path, size_t max_points = kMaxGeoJsonPoints);

/// `data` as GeoJSON text with the same top-level object it was read from, one feature per line
/// in a FeatureCollection, coordinates in the shortest form that reads back to the same double
/// (so a write / read round trip is exact), ids and properties as read. A kGeometry root whose
/// feature has no geometry is written as an empty GeometryCollection. Throws InvalidInput naming
/// the problem for data with a vector_data_problem or an id or properties that are not JSON.
std::string geojson_text(const VectorData& data);

/// The value of the property `key` of `feature` if its properties are an object whose `key` is a
/// string; empty otherwise.
std::optional<std::string> string_property(const Feature& feature, const std::string& key);

}  // namespace geolens
