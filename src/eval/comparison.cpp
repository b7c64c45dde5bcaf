#include "geolens/eval/comparison.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "geolens/core/errors.h"
#include "geolens/geometry/grid.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/lens/lens_method.h"
#include "lens/focus_lens.h"

namespace geolens {

double classic_radius(const Lens& lens, const LensOptions& options) {
  return options.model == LensModel::kFocus ? footprint_ratio(lens) * lens.region.reach()
                                            : lens.region.size();
}

CircleLens classic_target(const Lens& lens, const LensOptions& options, double zoom) {
  CircleLens target{lens.region.peak(), classic_radius(lens, options), zoom};
  if (options.model == LensModel::kFocus)
    target.focus_fraction = std::min(0.95, zoom / footprint_ratio(lens));
  return target;
}

std::vector<std::string> comparison_methods(const std::vector<Lens>& lenses,
                                            const LensOptions& options, const char* function) {
  std::vector<std::string> names = {"geometric"};
  for (size_t k = 0; k < lenses.size(); ++k) {
    for (size_t j = 0; j < k; ++j) {
      require((lenses[k].region.peak() - lenses[j].region.peak()).norm() >=
                  classic_radius(lenses[k], options) + classic_radius(lenses[j], options),
              function,
              "lenses " + std::to_string(j + 1) + " and " + std::to_string(k + 1) +
                  " overlap; compare needs lenses whose disks (peak, radius " +
                  number_text(classic_radius(lenses[j], options)) + " and " +
                  number_text(classic_radius(lenses[k], options)) + " px) are apart");
    }
  }
  for (ClassicLens kind : kClassicLenses) names.push_back(to_string(kind));
  return names;
}

std::vector<Eigen::Vector2d> footprint_outline(const Lens& lens, const LensOptions& options) {
  const Eigen::Vector2d peak = lens.region.peak();
  std::vector<Eigen::Vector2d> outline;
  const std::optional<std::vector<Eigen::Vector2d>> region = lens.region.outline();
  if (options.model == LensModel::kFocus && region && !lens.region.circle()) {
    const double ratio = footprint_ratio(lens);
    for (const Eigen::Vector2d& p : *region) outline.push_back(peak + ratio * (p - peak));
    return outline;
  }
  // A circle's footprint is its disk; so is that of a region without an outline, and the lift
  // models have none: the disk is the one measured.
  const double radius = classic_radius(lens, options);
  constexpr int kSides = 256;
  for (int i = 0; i < kSides; ++i) {
    const double angle = 2 * M_PI * i / kSides;
    outline.push_back(peak + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  return outline;
}

Comparison compare_lenses(int width, int height, const std::vector<Lens>& lenses,
                          const LensOptions& options, int baseline_mesh) {
  require(!lenses.empty(), "compare_lenses", "needs at least one lens");
  require(width > 0 && height > 0, "compare_lenses",
          "source size must be positive, got " + std::to_string(width) + " x " +
              std::to_string(height));
  require_mesh_vertices(baseline_mesh, "compare_lenses");
  comparison_methods(lenses, options, "compare_lenses");

  // The geometric lens, then the classic lenses matched to its measured zoom, over the same disk.
  Comparison c;
  c.width = width;
  c.height = height;
  c.lenses = lenses;
  c.geometric = GeometricLens(width, height, options).solve(lenses);
  std::vector<double> measure_radius;
  for (size_t k = 0; k < lenses.size(); ++k) {
    c.targets.push_back(
        classic_target(lenses[k], options, std::max(1.0, c.geometric.zoom_measured[k])));
    c.footprints.push_back(footprint_outline(lenses[k], options));
    measure_radius.push_back(zoom_measure_radius(lenses[k].region.size(),
                                                 c.geometric.box.sizes().maxCoeff(), options.mesh));
  }
  c.methods.push_back({"geometric", c.geometric.warp, c.geometric.zoom_measured, {}, {}, {}});
  // Each classic lens through the one lens call, on the targets as Lenses, measured over the
  // geometric lens's radius.
  std::vector<Lens> classic_lenses;
  for (const CircleLens& target : c.targets)
    classic_lenses.push_back(ClassicMethod::lens_for(target));
  for (ClassicLens kind : kClassicLenses) {
    const ClassicMethod method(kind, {baseline_mesh, measure_radius});
    Magnification matched = method.magnify(classic_lenses, width, height);
    c.methods.push_back(
        {method.name(), std::move(matched.warp), std::move(matched.zoom_measured), {}, {}, {}});
  }
  for (ComparedMethod& m : c.methods) {
    m.measures = measure_triangles(m.warp);
    m.regions = measure_regions(m.warp, m.measures, c.targets, width, height);
    m.foci = measure_foci(m.warp, m.measures, lenses);
  }
  c.eq7_energy = eq7_energy(c.geometric.lifted, c.geometric.mesh.F, c.geometric.flat).sum();
  return c;
}

double comparison_heat_max(const Comparison& comparison) {
  double heat_max = 0;
  for (const ComparedMethod& m : comparison.methods)
    heat_max = std::max(heat_max, m.regions.overall.conformal_max);
  return heat_max > 0 ? heat_max : 1;  // 0: every method is the identity
}

}  // namespace geolens
