#include <algorithm>
#include <cmath>
#include <functional>

#include "geolens/core/errors.h"
#include "geolens/source/map_style.h"

namespace geolens {

namespace {

constexpr double kMaxMercatorLatitude = 85.0511287798066;  // where Web Mercator is square
constexpr double kPi = 3.14159265358979323846;

// `g` with every coordinate row replaced by `f` of it.
void transform(Geometry& g, const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& f) {
  for (Eigen::MatrixX2d& path : g.paths)
    for (Eigen::Index i = 0; i < path.rows(); ++i)
      path.row(i) = f(path.row(i).transpose()).transpose();
  for (Geometry& member : g.members) transform(member, f);
}

}  // namespace

Eigen::Vector2d project(MapProjection projection, double lon, double lat) {
  if (projection == MapProjection::kPlateCarree) return {lon, lat};
  const double phi = std::clamp(lat, -kMaxMercatorLatitude, kMaxMercatorLatitude) * kPi / 180;
  return {lon * kPi / 180, std::log(std::tan(kPi / 4 + phi / 2))};
}

Eigen::Vector2d checked_degrees(double lon, double lat, const char* function,
                                const std::string& where) {
  const double t = kDegreeTolerance;
  require(lon >= -180 - t && lon <= 180 + t && lat >= -90 - t && lat <= 90 + t, function,
          where + ": the position (" + number_text(lon) + ", " + number_text(lat) +
              ") is not a longitude in [-180, 180] and a latitude in [-90, 90] (a vector map is "
              "in degrees, WGS84)");
  return {std::clamp(lon, -180.0, 180.0), std::clamp(lat, -90.0, 90.0)};
}

Eigen::Vector2d MapFrame::from_projected(const Eigen::Vector2d& p) const {
  return offset + scale * Eigen::Vector2d(p.x() - left, top - p.y());
}

Eigen::Vector2d MapFrame::pixels(double lon, double lat) const {
  return from_projected(project(projection, lon, lat));
}

Eigen::Vector2d MapFrame::degrees(const Eigen::Vector2d& pixel) const {
  const double x = left + (pixel.x() - offset.x()) / scale;
  const double y = top - (pixel.y() - offset.y()) / scale;
  if (projection == MapProjection::kPlateCarree) return {x, y};
  return {x * 180 / kPi, (2 * std::atan(std::exp(y)) - kPi / 2) * 180 / kPi};
}

VectorData to_frame_pixels(const VectorData& data, const MapFrame& frame, const std::string& name) {
  VectorData out = data;
  for (size_t f = 0; f < out.features.size(); ++f) {
    if (!out.features[f].geometry) continue;
    const std::string where = "'" + name + "': feature " + std::to_string(f);
    transform(*out.features[f].geometry, [&](const Eigen::Vector2d& p) {
      const Eigen::Vector2d d = checked_degrees(p.x(), p.y(), "to_frame_pixels", where);
      return frame.pixels(d.x(), d.y());
    });
  }
  return out;
}

VectorData to_degrees(const VectorData& data, const MapFrame& frame) {
  VectorData out = data;
  for (Feature& f : out.features)
    if (f.geometry)
      transform(*f.geometry, [&](const Eigen::Vector2d& p) { return frame.degrees(p); });
  return out;
}

PointTable to_frame_pixels(const PointTable& table, const MapFrame& frame,
                           const std::string& name) {
  PointTable out = table;
  for (Eigen::Index i = 0; i < out.points.rows(); ++i) {
    const Eigen::Vector2d d = checked_degrees(out.points(i, 0), out.points(i, 1), "to_frame_pixels",
                                              "'" + name + "': point " + std::to_string(i + 1));
    out.points.row(i) = frame.pixels(d.x(), d.y()).transpose();
  }
  return out;
}

PointTable to_degrees(const PointTable& table, const MapFrame& frame) {
  PointTable out = table;
  for (Eigen::Index i = 0; i < out.points.rows(); ++i)
    out.points.row(i) = frame.degrees(out.points.row(i).transpose()).transpose();
  return out;
}

}  // namespace geolens
