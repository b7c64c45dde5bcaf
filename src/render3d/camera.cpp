#include "geolens/render3d/camera.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <sstream>

#include "geolens/core/errors.h"

namespace geolens {

namespace {

double radians(double degrees) { return degrees * std::numbers::pi / 180; }

}  // namespace

void parse_view(const std::string& view, OrbitCamera& camera) {
  if (view.empty()) return;
  std::istringstream in(view);
  double azimuth = 0, elevation = 0;
  char comma = 0;
  std::string rest;
  const bool ok = bool(in >> azimuth) && bool(in >> comma) && comma == ',' &&
                  bool(in >> elevation) && !(in >> rest);
  require(ok && std::isfinite(azimuth) && std::isfinite(elevation), "parse_view",
          "view '" + view + "' is not AZ,EL (two numbers in degrees, e.g. 30,20)");
  require(elevation > -90 && elevation < 90, "parse_view",
          "view '" + view + "': the elevation must be in (-90, 90) degrees");
  camera.azimuth_degrees = azimuth;
  camera.elevation_degrees = elevation;
}

Eigen::Vector3d Projection::ray(double x, double y) const {
  const Eigen::Vector3d q((x - centre_x) / focal, -(y - centre_y) / focal, -1);
  return (rotation.transpose() * q).normalized();
}

Projection place_camera(const OrbitCamera& camera, const Eigen::Vector3d& centre, double radius,
                        int frame_width, int frame_height) {
  const char* f = "place_camera";
  require(frame_width >= 1 && frame_height >= 1, f,
          "the frame " + std::to_string(frame_width) + " x " + std::to_string(frame_height) +
              " is empty");
  require(std::isfinite(radius) && radius > 0 && centre.allFinite(), f,
          "the scene's bounding sphere (radius " + std::to_string(radius) + ") is empty");
  require(camera.elevation_degrees > -90 && camera.elevation_degrees < 90, f,
          "elevation " + std::to_string(camera.elevation_degrees) + " is not in (-90, 90)");
  require(std::isfinite(camera.azimuth_degrees), f, "the azimuth is not finite");
  require(camera.field_of_view_degrees > 0 && camera.field_of_view_degrees < 170, f,
          "field of view " + std::to_string(camera.field_of_view_degrees) +
              " is not in (0, 170) degrees");
  require(std::isfinite(camera.distance) && camera.distance >= 0, f,
          "distance " + std::to_string(camera.distance) + " is negative");
  const Eigen::Vector3d up = camera.up.normalized();
  Eigen::Vector3d front = camera.front - camera.front.dot(up) * up;
  require(up.allFinite() && camera.up.norm() > 0 && front.norm() > 1e-9 * camera.front.norm() &&
              front.norm() > 0,
          f, "the up and front axes are zero or parallel");
  front.normalize();
  const Eigen::Vector3d right = up.cross(front);
  const double az = radians(camera.azimuth_degrees), el = radians(camera.elevation_degrees);
  const Eigen::Vector3d toward_eye =
      std::cos(el) * (std::sin(az) * right + std::cos(az) * front) + std::sin(el) * up;

  const double half_v = radians(camera.field_of_view_degrees) / 2;
  const double half_h = std::atan(std::tan(half_v) * frame_width / frame_height);
  double distance = camera.distance;
  if (distance == 0) distance = radius / std::sin(std::min(half_v, half_h));
  require(distance > radius, f,
          "distance " + std::to_string(distance) + " puts the camera inside the scene (radius " +
              std::to_string(radius) + ")");

  Projection p;
  const Eigen::Vector3d z = toward_eye;
  const Eigen::Vector3d x = up.cross(z).normalized();
  const Eigen::Vector3d y = z.cross(x);
  p.rotation.row(0) = x;
  p.rotation.row(1) = y;
  p.rotation.row(2) = z;
  p.eye = centre + distance * toward_eye;
  p.focal = (frame_height / 2.0) / std::tan(half_v);
  p.centre_x = frame_width / 2.0;
  p.centre_y = frame_height / 2.0;
  return p;
}

void check_region(const PixelRegion& region, const char* function) {
  require(std::isfinite(region.pixel_size) && region.pixel_size > 0, function,
          "pixel size " + std::to_string(region.pixel_size) + " is not positive");
  require(region.width >= 1 && region.height >= 1 &&
              double(region.width) * region.height <= double(1 << 28),
          function,
          "region " + std::to_string(region.width) + " x " + std::to_string(region.height) +
              " is empty or larger than 2^28 pixels");
}

}  // namespace geolens
