#pragma once
// The style of a vector map (vector_map.h): its projection, its colours, which features each layer
// draws at which zoom, and which points it labels. Read from a JSON file (--style).

#include <Eigen/Core>
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geolens/io/vector_data.h"

namespace geolens {

/// A colour, each component in [0, 1], straight (not premultiplied) alpha.
struct MapColor {
  ///@{
  double r = 0, g = 0, b = 0, a = 1;  ///< red, green, blue, alpha
  ///@}
};

/// How a vector map lays longitude and latitude (degrees) on its plane (a style's "projection").
enum class MapProjection {
  kWebMercator,  ///< "web_mercator": x = lon, y = ln tan(pi/4 + lat/2), lat clamped to +-85.0511
  kPlateCarree,  ///< "plate_carree": x = lon, y = lat (equirectangular)
};

/// How a layer labels its points.
struct MapLabelStyle {
  /// Properties holding the text, the first that is a non-empty string wins.
  std::vector<std::string> text = {"nameascii", "name"};
  std::string rank = "scalerank";  ///< a number property; a point without it has rank 0
  /// A label of rank r shows where the local scale (screen pixels per frame pixel) is at least
  /// 2^(r - base): at zoom 1 ranks <= base, each doubling of the zoom one rank more.
  double base = 3;
  double size = 12;                     ///< font size, screen pixels
  MapColor color = {0.1, 0.1, 0.1, 1};  ///< the text's
  MapColor halo = {1, 1, 1, 0.9};       ///< the outline around the text, halo_width wide
  double halo_width = 2;                ///< screen pixels, >= 0
};

/// One layer: the features it selects and how it draws them, in the order of the layers (a later
/// layer draws over an earlier one; a feature selected by several layers is drawn by each).
struct MapLayerStyle {
  std::string name;  ///< for messages
  /// Selects the features whose property `key` equals one of `values` (JSON equality: 2 and 2.0
  /// match, "2" and 2 do not), for every entry; empty: every feature.
  struct Condition {
    std::string key;                  ///< a property name
    std::vector<std::string> values;  ///< each a JSON value as text
  };
  std::vector<Condition> where;  ///< all must hold; empty: every feature
  /// Which geometries of the selected features it draws (and, for points, labels).
  enum class Geometry { kAny, kPoint, kLine, kPolygon } geometry = Geometry::kAny;  ///< kAny: all
  std::optional<MapColor> fill;    ///< polygons, and point dots; none: not filled
  std::optional<MapColor> stroke;  ///< lines and polygon outlines; none: not stroked
  /// Stroke width and point radius in pixels of the level drawn, which is shown at about one
  /// texel per screen pixel: so widths stay the same on screen at every zoom, as on a web map,
  /// and the focus shows more of them rather than fatter ones.
  double width = 1;
  /// Point dots; 0: points are not drawn (but may be labelled). The points of a layer with a
  /// label are drawn over the output, upright, `radius` screen pixels (vector_map.h).
  double radius = 0;
  /// The layer is drawn on the levels whose zoom is in [min_zoom, max_zoom): level l of a map of
  /// scale s is the one shown where the frame is magnified s / 2^l times (level 0 of a scale-8
  /// map: zoom 8); the renderer blends neighbouring levels, so a layer fades in over a zoom band.
  ///@{
  double min_zoom = 0, max_zoom = std::numeric_limits<double>::infinity();
  ///@}
  /// Labels of its points (of Point and MultiPoint geometries), shown where the local scale is
  /// in [min_zoom, max_zoom) and allows their rank (map_labels.h).
  std::optional<MapLabelStyle> label;
};

/// A vector map's style: what parse_map_style reads, or default_map_style.
struct MapStyle {
  MapColor background = {0.67, 0.8, 0.9, 1};               ///< opaque: the alpha is ignored
  MapProjection projection = MapProjection::kWebMercator;  ///< how the frame shows the globe
  /// [west, south, east, north], degrees: what the frame shows; empty: the data's bounding box.
  std::optional<std::array<double, 4>> extent;
  std::vector<MapLayerStyle> layers;  ///< drawn in order, each over the ones before
};

/// The style used without a style file: water-blue background; three layers over every feature:
/// polygons filled light beige with a grey outline, lines grey 1 px, points as dark 2 px dots
/// labelled with the default MapLabelStyle (Natural Earth's nameascii or name, ranked by
/// scalerank).
MapStyle default_map_style();

/// Parses a style document. The schema (every member optional; colours "#rgb", "#rrggbb" or
/// "#rrggbbaa"; zooms, widths and sizes numbers):
///
///     {"background": "#aaccee", "projection": "web_mercator" | "plate_carree",
///      "extent": [west, south, east, north],
///      "layers": [{"name": "places", "where": {"featurecla": ["Populated place", ...]},
///                  "geometry": "any" | "point" | "line" | "polygon",
///                  "fill": "#333", "stroke": "#888", "width": 1, "radius": 2,
///                  "min_zoom": 0, "max_zoom": 8,
///                  "label": {"text": ["nameascii", "name"], "rank": "scalerank", "base": 3,
///                            "size": 12, "color": "#222", "halo": "#ffffffe0",
///                            "halo_width": 2}}]}
///
/// A "where" value is a value or a list of values (strings, numbers, booleans). "text" is a
/// property name or a list. A "layers" member replaces the default's layers; without it the
/// default's layers are kept. An unknown key is refused (so a typo does not pass silently).
/// @param name  where the text came from (a file name), for messages
/// Throws InvalidInput("map_style: '<name>': <key path>: <what>"), e.g. "layers[2].fill: '#12'
/// is not a colour", for text that is not JSON (with its line and column), an unknown key, a
/// value of the wrong kind or out of range (widths and radii in [0, 1000], a label size in
/// [1, 1000], min_zoom <= max_zoom, an extent with west < east and south < north within +-180
/// and +-90).
MapStyle parse_map_style(const std::string& text, const std::string& name);

/// parse_map_style of the file at `path`. Throws InvalidInput naming the path if it cannot be
/// read.
MapStyle read_map_style(const std::string& path);

// Where a longitude and latitude lie in a vector map's frame, and back: its projection and the
// uniform scale and offset that fit its extent to the frame (vector_map.h). So data in degrees
// can be placed on a vector map's frame (geolens map, magnify --overlay) and picked points told
// in degrees.

/// How far past [-180, 180] x [-90, 90] a position may be and still be read, clamped, degrees:
/// the rounding of the tools that wrote it (Natural Earth's land has 180.00000000000014).
constexpr double kDegreeTolerance = 1e-9;

/// (lon, lat) degrees projected by `projection`, y north: plate carree (lon, lat) as they are, Web
/// Mercator in radians (latitudes clamped to +-85.0511, where its map is square).
Eigen::Vector2d project(MapProjection projection, double lon, double lat);

/// (lon, lat) if within kDegreeTolerance of [-180, 180] x [-90, 90], clamped to it; else throws
/// InvalidInput naming `function` and `where` (e.g. "feature 3") with the value's digits.
Eigen::Vector2d checked_degrees(double lon, double lat, const char* function,
                                const std::string& where);

/// A vector map's frame: projected (x, y north) -> frame pixels (x right, y down) is
/// offset + scale (x - left, top - y).
struct MapFrame {
  MapProjection projection = MapProjection::kWebMercator;  ///< the map style's
  ///@{
  double left = 0, top = 0;  ///< the projected extent's west and north edges
  ///@}
  double scale = 1;                                  ///< frame pixels per projected unit, > 0
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();  ///< frame pixels of (left, top)

  /// A projected point in frame pixels.
  Eigen::Vector2d from_projected(const Eigen::Vector2d& p) const;
  /// (lon, lat) degrees in frame pixels.
  Eigen::Vector2d pixels(double lon, double lat) const;
  /// Frame pixels in (lon, lat) degrees: pixels' inverse (longitudes beyond +-180 and, for Web
  /// Mercator, latitudes beyond +-85.0511 where the pixel is outside the map).
  Eigen::Vector2d degrees(const Eigen::Vector2d& pixel) const;
};

/// Every coordinate of `data` (degrees, checked_degrees; `name` the input, for messages) in
/// `frame`'s pixels, or back (to_degrees).
VectorData to_frame_pixels(const VectorData& data, const MapFrame& frame, const std::string& name);
/// Every coordinate of `data`, in `frame`'s pixels, in degrees (MapFrame::degrees: off the map,
/// beyond the globe's range; not checked).
VectorData to_degrees(const VectorData& data, const MapFrame& frame);
/// The same for points (x = lon, y = lat), their rows' rest kept.
PointTable to_frame_pixels(const PointTable& table, const MapFrame& frame, const std::string& name);
/// The points of `table`, in `frame`'s pixels, in degrees (x = lon, y = lat) as to_degrees above,
/// their rows' rest kept.
PointTable to_degrees(const PointTable& table, const MapFrame& frame);

}  // namespace geolens
