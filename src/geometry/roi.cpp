#include "geolens/geometry/roi.h"

#include <algorithm>
#include <cmath>

#include "geolens/core/errors.h"
#include "geometry/roi_impl.h"

namespace geolens {

namespace {

// A region moved: the one it was, read at p - offset.
class TranslatedShape final : public RegionShape {
 public:
  TranslatedShape(std::shared_ptr<const RegionShape> base, const Eigen::Vector2d& offset)
      : base_(std::move(base)), offset_(offset) {}
  const std::shared_ptr<const RegionShape>& base() const { return base_; }
  const Eigen::Vector2d& offset() const { return offset_; }

  std::string kind() const override { return base_->kind(); }
  Eigen::AlignedBox2d bounds() const override {
    const Eigen::AlignedBox2d b = base_->bounds();
    return Eigen::AlignedBox2d(b.min() + offset_, b.max() + offset_);
  }
  Eigen::Vector2d peak() const override { return base_->peak() + offset_; }
  double size() const override { return base_->size(); }
  double reach() const override { return base_->reach(); }
  double depth(const Eigen::Vector2d& p) const override { return base_->depth(p - offset_); }
  double thickness(const Eigen::Vector2d& p) const override {
    return base_->thickness(p - offset_);
  }
  double distance(const Eigen::Vector2d& p) const override { return base_->distance(p - offset_); }
  std::vector<Eigen::Vector2d> anchors() const override { return moved(base_->anchors()); }
  std::optional<std::vector<Eigen::Vector2d>> outline() const override {
    std::optional<std::vector<Eigen::Vector2d>> o = base_->outline();
    if (o) *o = moved(std::move(*o));
    return o;
  }

 private:
  std::vector<Eigen::Vector2d> moved(std::vector<Eigen::Vector2d> points) const {
    for (Eigen::Vector2d& p : points) p += offset_;
    return points;
  }
  std::shared_ptr<const RegionShape> base_;
  Eigen::Vector2d offset_;
};

}  // namespace

Region::Region(std::shared_ptr<const RegionShape> shape) : shape_(std::move(shape)) {
  require(shape_ != nullptr, "Region", "the shape is null");
}

Region Region::circle(const Eigen::Vector2d& center, double radius) {
  require(center.allFinite(), "Region::circle", "centre is not finite");
  require(std::isfinite(radius) && radius > 0, "Region::circle",
          "radius must be a positive number, got " + number_text(radius));
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

Region Region::translated(const Eigen::Vector2d& offset) const {
  require(offset.allFinite(), "Region::translated", "the offset is not finite");
  if (const std::optional<Circle> c = circle())
    return Region::circle(c->center + offset, c->radius);
  // A region moved before is moved from where it began: a drag adds no layer per frame.
  if (const auto* moved = dynamic_cast<const TranslatedShape*>(shape_.get()))
    return Region(std::make_shared<TranslatedShape>(moved->base(), moved->offset() + offset));
  return Region(std::make_shared<TranslatedShape>(shape_, offset));
}

}  // namespace geolens
