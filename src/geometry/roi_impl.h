#pragma once
// Private: the region shape behind geolens's own regions (roi.h): its fields as functions,
// analytic for a circle, sampled from a raster for a polygon or a mask blob.

#include <functional>

#include "geolens/geometry/roi.h"

namespace geolens {

struct FieldShape final : RegionShape {
  std::string name;
  Eigen::AlignedBox2d box;
  Eigen::Vector2d peak_point = Eigen::Vector2d::Zero();
  double largest_thickness = 0;
  double largest_reach = 0;
  std::vector<Eigen::Vector2d> anchor_points;
  std::optional<Circle> as_circle;
  std::optional<std::vector<Eigen::Vector2d>> as_polygon;
  std::function<double(const Eigen::Vector2d&)> depth_at, thickness_at, distance_at;

  std::string kind() const override { return name; }
  Eigen::AlignedBox2d bounds() const override { return box; }
  Eigen::Vector2d peak() const override { return peak_point; }
  double size() const override { return largest_thickness; }
  double reach() const override { return largest_reach; }
  double depth(const Eigen::Vector2d& p) const override { return depth_at(p); }
  double thickness(const Eigen::Vector2d& p) const override { return thickness_at(p); }
  double distance(const Eigen::Vector2d& p) const override { return distance_at(p); }
  std::vector<Eigen::Vector2d> anchors() const override { return anchor_points; }
  std::optional<Circle> circle() const override { return as_circle; }
  std::optional<std::vector<Eigen::Vector2d>> outline() const override { return as_polygon; }
};

}  // namespace geolens
