#include "eval/lens_json.h"

#include "geolens/lens/lens_options.h"
#include "lens/focus_lens.h"

namespace geolens {

nlohmann::json lens_json(const Lens& lens, double zoom_measured, const FocusMeasure& focus,
                         LensModel model) {
  const Region& region = lens.region;
  const Eigen::AlignedBox2d box = region.bounds();
  nlohmann::json json = {{"kind", region.kind()},
                         {"bbox", {box.min().x(), box.min().y(), box.max().x(), box.max().y()}},
                         {"peak", {region.peak().x(), region.peak().y()}},
                         {"size", region.size()},
                         {"profile", to_string(lens.profile)},
                         {"zoom_requested", lens.zoom},
                         {"zoom_measured", zoom_measured},
                         {"footprint", footprint_ratio(lens)},
                         {"focus",
                          {{"zoom", focus.zoom},
                           {"uniformity", focus.uniformity},
                           {"shape_mean", focus.shape_mean},
                           {"shape_max", focus.shape_max}}},
                         {"footprint_radius", focus.footprint_radius},
                         {"displacement_beyond_footprint", focus.displacement_beyond_footprint}};
  LensOptions solved;
  solved.model = model;
  for (const char* name : {"profile", "footprint"})
    if (!reads_option(solved, {lens}, name)) json.erase(name);
  if (const std::optional<Circle> circle = region.circle()) {
    json["center"] = {circle->center.x(), circle->center.y()};
    json["radius"] = circle->radius;
  }
  return json;
}

}  // namespace geolens
