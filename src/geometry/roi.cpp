#include "geolens/geometry/roi.h"

#include <algorithm>
#include <cmath>

#include "geolens/core/errors.h"
#include "geometry/roi_impl.h"

namespace geolens {

Region::Region(std::shared_ptr<const RegionShape> shape) : shape_(std::move(shape)) {
  require(shape_ != nullptr, "Region", "the shape is null");
}

Region Region::circle(const Eigen::Vector2d& center, double radius) {
  require(center.allFinite(), "Region::circle", "centre is not finite");
  require(std::isfinite(radius) && radius > 0, "Region::circle",
          "radius must be a positive number, got " + std::to_string(radius));
  auto shape = std::make_shared<FieldShape>();
  shape->name = "circle";
  shape->box = Eigen::AlignedBox2d(center.array() - radius, center.array() + radius);
  shape->peak_point = center;
  shape->largest_thickness = radius;
  shape->largest_reach = radius;
  shape->anchor_points = {center};
  shape->as_circle = Circle{center, radius};
  shape->depth_at = [center, radius](const Eigen::Vector2d& p) {
    const double d = (p - center).norm();
    return d >= radius ? 0.0 : 1.0 - d / radius;
  };
  shape->thickness_at = [radius](const Eigen::Vector2d&) { return radius; };
  shape->distance_at = [center, radius](const Eigen::Vector2d& p) {
    return std::max(0.0, (p - center).norm() - radius);
  };
  return Region(std::move(shape));
}

std::string Region::kind() const { return shape_->kind(); }
std::optional<Circle> Region::circle() const { return shape_->circle(); }
std::optional<std::vector<Eigen::Vector2d>> Region::outline() const { return shape_->outline(); }
Eigen::AlignedBox2d Region::bounds() const { return shape_->bounds(); }
Eigen::Vector2d Region::peak() const { return shape_->peak(); }
double Region::size() const { return shape_->size(); }
double Region::depth(const Eigen::Vector2d& p) const { return shape_->depth(p); }
double Region::thickness(const Eigen::Vector2d& p) const { return shape_->thickness(p); }
double Region::distance(const Eigen::Vector2d& p) const { return shape_->distance(p); }
double Region::reach() const { return shape_->reach(); }
std::vector<Eigen::Vector2d> Region::anchors() const { return shape_->anchors(); }

}  // namespace geolens
