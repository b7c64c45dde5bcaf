#pragma once
// Private: the shared state behind geolens::Region (roi.h).

#include <functional>

#include "geolens/geometry/roi.h"

namespace geolens {

struct Region::Impl {
  RegionKind kind = RegionKind::kCircle;
  Eigen::AlignedBox2d bounds;
  Eigen::Vector2d peak = Eigen::Vector2d::Zero();
  double size = 0;
  double reach = 0;
  std::vector<Eigen::Vector2d> vertices;  // polygons only
  // The two fields (see roi.h), analytic for a circle, sampled from a raster otherwise.
  std::function<double(const Eigen::Vector2d&)> depth;
  std::function<double(const Eigen::Vector2d&)> thickness;
  std::function<double(const Eigen::Vector2d&)> distance;  // 0 inside
};

}  // namespace geolens
