#include "geolens/geometry/roi.h"

#include <algorithm>
#include <cmath>

#include "geolens/core/errors.h"
#include "geometry/roi_impl.h"

namespace geolens {

std::string to_string(RegionKind kind) {
  switch (kind) {
    case RegionKind::kCircle:
      return "circle";
    case RegionKind::kPolygon:
      return "polygon";
    case RegionKind::kMask:
      return "mask";
  }
  return "?";
}

Region::Region(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

Region Region::circle(const Eigen::Vector2d& center, double radius) {
  require(center.allFinite(), "Region::circle", "centre is not finite");
  require(std::isfinite(radius) && radius > 0, "Region::circle",
          "radius must be a positive number, got " + std::to_string(radius));
  auto impl = std::make_shared<Impl>();
  impl->kind = RegionKind::kCircle;
  impl->bounds = Eigen::AlignedBox2d(center.array() - radius, center.array() + radius);
  impl->peak = center;
  impl->size = radius;
  impl->depth = [center, radius](const Eigen::Vector2d& p) {
    const double d = (p - center).norm();
    return d >= radius ? 0.0 : 1.0 - d / radius;
  };
  impl->thickness = [radius](const Eigen::Vector2d&) { return radius; };
  impl->distance = [center, radius](const Eigen::Vector2d& p) {
    return std::max(0.0, (p - center).norm() - radius);
  };
  impl->reach = radius;
  return Region(std::move(impl));
}

RegionKind Region::kind() const { return impl_->kind; }
Eigen::AlignedBox2d Region::bounds() const { return impl_->bounds; }
Eigen::Vector2d Region::peak() const { return impl_->peak; }
double Region::size() const { return impl_->size; }
double Region::depth(const Eigen::Vector2d& p) const { return impl_->depth(p); }
double Region::thickness(const Eigen::Vector2d& p) const { return impl_->thickness(p); }
double Region::distance(const Eigen::Vector2d& p) const { return impl_->distance(p); }
double Region::reach() const { return impl_->reach; }
const std::vector<Eigen::Vector2d>& Region::vertices() const { return impl_->vertices; }

}  // namespace geolens
