#pragma once
// Vector data mapped through a warp: features (GeoJSON) and point tables (CSV), forward (source
// -> screen) or inverse (screen -> source), lines and rings densified so that they bend with it.

#include "geolens/io/vector_data.h"
#include "geolens/warp/warp_map.h"

namespace geolens {

/// Which way the data goes through the warp.
enum class MapDirection {
  kForward,  ///< source pixels -> screen pixels (WarpMap::forward)
  kInverse,  ///< screen pixels -> source pixels (WarpMap::inverse)
};

/// How map_features maps: which way, and how finely lines and rings are cut first.
struct MapOptions {
  MapDirection direction = MapDirection::kForward;  ///< source -> screen, or back
  /// Lines and rings are densified (densify.h) to segments of at most this length before they
  /// are mapped, in pixels of the side they are mapped from (source for kForward, screen for
  /// kInverse), > 0; +infinity maps their vertices alone. The warp is linear on each triangle, so
  /// segments shorter than the mesh's triangles follow it closely.
  double max_segment = 2.0;
};

/// What the mapping left out, because it lies outside the area the warp covers (where WarpMap
/// says "nowhere": outside the image for forward, outside the framed output for inverse, the
/// ring a zoom-in lens hides).
struct MapLosses {
  int points = 0;    ///< points dropped (of Point and MultiPoint geometries, or CSV rows)
  int lines = 0;     ///< lines (of LineString and MultiLineString geometries) cut or dropped
  int polygons = 0;  ///< polygons (of Polygon and MultiPolygon geometries) dropped
  bool any() const { return points > 0 || lines > 0 || polygons > 0; }  ///< anything left out
};

/// What map_features returns.
struct MappedFeatures {
  VectorData data;   ///< the mapped features, in the pixels of the side mapped to
  MapLosses losses;  ///< what was cut or dropped
};

/// What map_points returns.
struct MappedPoints {
  PointTable table;  ///< the rows kept, their points in the pixels of the side mapped to
  MapLosses losses;  ///< the rows dropped, as `points`
};

/// Maps every geometry of `data` through `map`, ids and properties unchanged:
/// - a point (of a Point or MultiPoint) maps on its own; one outside the covered area is
///   dropped;
/// - a line (of a LineString or MultiLineString) is densified, then every vertex is mapped; where
///   it leaves the covered area it is cut, each piece ending at the area's border (found by
///   bisection on the segment, to 2^-40 of its length), and the pieces of 2 or more vertices
///   are kept: a LineString cut into several becomes a MultiLineString;
/// - a polygon (of a Polygon or MultiPolygon) is mapped ring by ring, densified; a polygon with
///   any ring vertex outside the covered area is dropped whole (a ring cut open is no ring);
/// - a GeometryCollection maps its members.
/// A geometry left with nothing (every part dropped, or none to begin with) becomes null (RFC 7946
/// lets a reader take an empty geometry as null), a member of a GeometryCollection is removed; a
/// bare geometry (GeoJsonRoot::kGeometry) left with nothing is written as an empty
/// GeometryCollection (geojson.h). Only the densified vertices are tested: a line or ring passing
/// through an uncovered gap narrower than max_segment between two covered vertices is not cut
/// there. Throws InvalidInput naming "map_features" for data with a vector_data_problem or
/// max_segment not > 0.
MappedFeatures map_features(const VectorData& data, const WarpMap& map,
                            const MapOptions& options = {});

/// Maps every point of `table` through `map`; a row whose point is outside the covered area is
/// dropped with its `rest`, the header kept. Throws InvalidInput naming "map_points" if rest
/// does not have a row per point or a point is not finite.
MappedPoints map_points(const PointTable& table, const WarpMap& map, MapDirection direction);

}  // namespace geolens
