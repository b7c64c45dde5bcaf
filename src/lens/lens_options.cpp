#include "geolens/lens/lens_options.h"

#include <cmath>
#include <string>

#include "core/enum_names.h"
#include "core/thread_pool.h"
#include "geolens/core/errors.h"
#include "geolens/geometry/grid.h"

namespace geolens {

namespace {

// The names of each enum, in the order a parser's error lists them.
constexpr EnumName<FlattenWeights> kFlattenWeights[] = {{FlattenWeights::kPaper, "paper"},
                                                        {FlattenWeights::kCotan, "cotan"}};
constexpr EnumName<Metric> kMetrics[] = {{Metric::kPaper, "paper"},
                                         {Metric::kSpectrum, "spectrum"}};
constexpr EnumName<Boundary> kBoundaries[] = {
    {Boundary::kSliding, "sliding"}, {Boundary::kFixed, "fixed"}, {Boundary::kFree, "free"}};
constexpr EnumName<TextureWeights> kTextureWeights[] = {{TextureWeights::kCotan, "cotan"},
                                                        {TextureWeights::kPositiveCotan, "cotan+"},
                                                        {TextureWeights::kMeanValue, "mvc"}};
constexpr EnumName<Extent> kExtents[] = {{Extent::kGlobal, "global"}, {Extent::kLocal, "local"}};
constexpr EnumName<LensModel> kLensModels[] = {{LensModel::kFocus, "focus"},
                                               {LensModel::kLift, "lift"},
                                               {LensModel::kField, "field"},
                                               {LensModel::kAuto, "auto"}};

}  // namespace

FlattenWeights parse_flatten_weights(const std::string& name) {
  return parse_enum(kFlattenWeights, name, "parse_flatten_weights", "weights");
}
Metric parse_metric(const std::string& name) {
  return parse_enum(kMetrics, name, "parse_metric", "metric");
}
Boundary parse_boundary(const std::string& name) {
  return parse_enum(kBoundaries, name, "parse_boundary", "boundary");
}
TextureWeights parse_texture_weights(const std::string& name) {
  return parse_enum(kTextureWeights, name, "parse_texture_weights", "texture weights");
}
Extent parse_extent(const std::string& name) {
  return parse_enum(kExtents, name, "parse_extent", "extent");
}
LensModel parse_lens_model(const std::string& name) {
  return parse_enum(kLensModels, name, "parse_lens_model", "lens model");
}

std::string to_string(FlattenWeights weights) { return enum_name(kFlattenWeights, weights); }
std::string to_string(Metric metric) { return enum_name(kMetrics, metric); }
std::string to_string(Boundary boundary) { return enum_name(kBoundaries, boundary); }
std::string to_string(TextureWeights weights) { return enum_name(kTextureWeights, weights); }
std::string to_string(Extent extent) { return enum_name(kExtents, extent); }
std::string to_string(LensModel model) { return enum_name(kLensModels, model); }

LensModel resolved_model(LensModel model, const std::vector<Lens>& lenses) {
  if (model != LensModel::kAuto) return model;
  for (const Lens& lens : lenses)
    if (!lens.region.circle()) return LensModel::kField;
  return LensModel::kLift;
}

void validate(const FlattenOptions& o) {
  const double alpha_max = o.metric == Metric::kPaper ? 1.0 : 1.0 + 1e-12;
  require_option(std::isfinite(o.alpha) && o.alpha >= 0 && o.alpha < alpha_max, "validate", "alpha",
                 "must be in " + std::string(o.metric == Metric::kPaper ? "[0, 1)" : "[0, 1]") +
                     " for metric " + to_string(o.metric) + ", got " + number_text(o.alpha));
  require_option(std::isfinite(o.tolerance) && o.tolerance > 0 && o.tolerance < 1, "validate",
                 "tolerance", "must be in (0, 1), got " + number_text(o.tolerance));
  require_option(o.max_iterations >= 1 && o.max_iterations <= 100000, "validate", "max_iterations",
                 "must be in [1, 100000], got " + std::to_string(o.max_iterations));
  require_option(o.threads >= 0 && o.threads <= ThreadPool::kMaxThreads, "validate", "threads",
                 "must be in [0, " + std::to_string(ThreadPool::kMaxThreads) + "], got " +
                     std::to_string(o.threads));
}

void validate(const LensOptions& o) {
  require_option(std::isfinite(o.extent_factor) && o.extent_factor > 1 && o.extent_factor <= 100,
                 "validate", "extent_factor",
                 "must be in (1, 100], got " + number_text(o.extent_factor));
  require_mesh_vertices(o.mesh, "validate");
  if (o.draft_mesh != 0) require_mesh_vertices(o.draft_mesh, "validate", "draft_mesh");
  // Finer than a hundredth of a pixel shows nothing and refines without end (1e-9 ran away).
  require_option(
      std::isfinite(o.mesh_tolerance) && (o.mesh_tolerance == 0 || o.mesh_tolerance >= 0.01),
      "validate", "mesh_tolerance",
      "must be 0 (no refinement) or at least 0.01 pixels, got " + number_text(o.mesh_tolerance));
  require(std::isfinite(o.zoom_tolerance) && o.zoom_tolerance > 0, "validate",
          "zoom tolerance must be positive");
  require(o.max_calibration_solves >= 1, "validate", "at least one calibration solve needed");
  validate(o.subdivision);
  validate(o.flatten);
}

}  // namespace geolens
