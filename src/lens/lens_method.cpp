#include "geolens/lens/lens_method.h"

#include <algorithm>
#include <string>
#include <utility>

#include "geolens/core/errors.h"
#include "geolens/measure/distortion.h"
#include "lens/focus_lens.h"

namespace geolens {

namespace {

// The largest flat top a classic lens built from a Lens gets, as a fraction of its radius: the
// rest is its drop-off.
constexpr double kMaxFocusFraction = 0.95;

}  // namespace

GeometricMethod::GeometricMethod(const LensOptions& options) : options_(options) {
  validate(options);
}

Magnification GeometricMethod::magnify(const std::vector<Lens>& lenses, double width,
                                       double height) const {
  return GeometricLens(width, height, options_).solve(lenses);
}

ClassicMethod::ClassicMethod(ClassicLens kind, ClassicOptions options)
    : kind_(kind), options_(std::move(options)) {
  require_mesh_vertices(options_.mesh, "ClassicMethod");
}

CircleLens ClassicMethod::circle_lens(const Lens& lens) {
  const std::optional<Circle> circle = lens.region.circle();
  require(circle.has_value(), "ClassicMethod",
          "a classic lens is radial: the region must be a circle, got a " + lens.region.kind());
  const double footprint = footprint_ratio(lens);
  return CircleLens{circle->center, footprint * circle->radius, lens.zoom,
                    std::min(kMaxFocusFraction, lens.zoom / footprint)};
}

Lens ClassicMethod::lens_for(const CircleLens& circle) {
  validate(circle, "ClassicMethod::lens_for");
  require(circle.focus_fraction <= kMaxFocusFraction, "ClassicMethod::lens_for",
          "focus fraction must be at most " + std::to_string(kMaxFocusFraction) + ", got " +
              std::to_string(circle.focus_fraction));
  const double footprint = circle.zoom / circle.focus_fraction;
  return Lens{Region::circle(circle.center, circle.radius / footprint), circle.zoom,
              Profile::kGaussian, footprint};
}

Magnification ClassicMethod::magnify(const std::vector<Lens>& lenses, double width,
                                     double height) const {
  require(options_.measure_radius.empty() || options_.measure_radius.size() == lenses.size(),
          "ClassicMethod", "need one measure radius per lens, or none");
  std::vector<CircleLens> targets;
  std::vector<double> measure_radius = options_.measure_radius;
  for (const Lens& lens : lenses) {
    validate_lens(lens, width, height);
    targets.push_back(circle_lens(lens));
    if (options_.measure_radius.empty())
      measure_radius.push_back(
          zoom_measure_radius(lens.region.size(), std::max(width, height), options_.mesh));
  }
  return match_classic_lens(kind_, targets, measure_radius, width, height, options_.mesh);
}

std::vector<std::unique_ptr<LensMethod>> every_method(const LensOptions& options,
                                                      const ClassicOptions& classic) {
  std::vector<std::unique_ptr<LensMethod>> methods;
  methods.push_back(std::make_unique<GeometricMethod>(options));
  for (ClassicLens kind : kClassicLenses)
    methods.push_back(std::make_unique<ClassicMethod>(kind, classic));
  return methods;
}

}  // namespace geolens
