#pragma once
// Where a longitude and latitude lie in a vector map's frame, and back: its projection and the
// uniform scale and offset that fit its extent to the frame (vector_map.h). So data in degrees
// can be placed on a vector map's frame (geolens map, magnify --overlay) and picked points told
// in degrees.

#include <Eigen/Core>
#include <string>

#include "geolens/io/vector_data.h"
#include "geolens/source/map_style.h"

namespace geolens {

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
  MapProjection projection = MapProjection::kWebMercator;
  double left = 0, top = 0;  ///< the projected extent's west and north edges
  double scale = 1;          ///< frame pixels per projected unit, > 0
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
VectorData to_degrees(const VectorData& data, const MapFrame& frame);
/// The same for points (x = lon, y = lat), their rows' rest kept.
PointTable to_frame_pixels(const PointTable& table, const MapFrame& frame, const std::string& name);
PointTable to_degrees(const PointTable& table, const MapFrame& frame);

}  // namespace geolens
