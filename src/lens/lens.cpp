#include "geolens/lens/lens.h"

#include <cmath>
#include <string>

#include "geolens/core/errors.h"

namespace geolens {

void require_zoom(double zoom, const char* function) {
  require(std::isfinite(zoom) && zoom >= kMinZoom && zoom <= kMaxZoom, function,
          "zoom must be in [" + number_text(kMinZoom) + ", " + number_text(kMaxZoom) + "], got " +
              number_text(zoom));
}

void validate_lens(const Lens& lens, double width, double height) {
  auto inside = [&](const Eigen::Vector2d& p) {
    return p.x() >= 0 && p.x() <= width && p.y() >= 0 && p.y() <= height;
  };
  auto where = [](const Eigen::Vector2d& p) {
    return "(" + number_text(p.x()) + ", " + number_text(p.y()) + ")";
  };
  const std::string image = std::to_string(int(width)) + "x" + std::to_string(int(height));
  // A circle's centre, a polygon's vertices: the points that define the region.
  const std::string what = lens.region.circle() ? "lens centre" : lens.region.kind() + " vertex";
  for (const Eigen::Vector2d& v : lens.region.anchors()) {
    require(inside(v), "validate_lens",
            what + " " + where(v) + " is outside the " + image + " image");
  }
  // A region under half a pixel has nothing to magnify, and no mesh (a radius of 1e-308 was
  // refused by make_grid for a box of 0 x 0).
  require(lens.region.reach() >= 0.5, "validate_lens",
          "the " + lens.region.kind() + " reaches " + number_text(lens.region.reach()) +
              " px from its centre, less than half a pixel");
  require_zoom(lens.zoom, "validate_lens");
  require_option(lens.footprint == 0 || (std::isfinite(lens.footprint) &&
                                         lens.footprint > lens.zoom && lens.footprint <= 100),
                 "validate_lens", "footprint",
                 "must be 0 (default) or in (zoom, 100] = (" + number_text(lens.zoom) +
                     ", 100], got " + number_text(lens.footprint));
}

}  // namespace geolens
