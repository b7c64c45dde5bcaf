#include "geolens/lens/lens_options.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>

#include "core/enum_names.h"
#include "core/thread_pool.h"
#include "geolens/core/errors.h"
#include "geolens/core/parse.h"
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

namespace {

int integer(const std::string& text, const char* name) {
  const std::optional<int> value = read_integer(text);
  if (!value) throw InvalidOption("LensOptions", name, "must be an integer, got '" + text + "'");
  return *value;
}

double number(const std::string& text, const char* name) {
  const std::optional<double> value = read_number(text);
  if (!value) throw InvalidOption("LensOptions", name, "must be a number, got '" + text + "'");
  return *value;
}

// The rows of the table, each from the member it reads and writes: `access` is a generic lambda
// [](auto& o) -> auto& { return o.member; }, for the getter (const) and the setter alike.
template <class Access>
LensOptionField integer_field(const char* name, const char* help, Access access) {
  return {
      name,
      LensOptionField::Type::kInteger,
      help,
      {},
      [access](const LensOptions& o) { return std::to_string(access(o)); },
      [access, name](LensOptions& o, const std::string& text) { access(o) = integer(text, name); }};
}

template <class Access>
LensOptionField number_field(const char* name, const char* help, Access access) {
  return {
      name,
      LensOptionField::Type::kNumber,
      help,
      {},
      [access](const LensOptions& o) { return number_text(access(o)); },
      [access, name](LensOptions& o, const std::string& text) { access(o) = number(text, name); }};
}

template <class Enum, std::size_t N, class Access>
LensOptionField choice_field(const char* name, const char* help, const EnumName<Enum> (&names)[N],
                             Access access) {
  std::vector<std::string> choices;
  for (const EnumName<Enum>& entry : names) choices.push_back(entry.name);
  const std::string listed = enum_list(names);
  return {name,
          LensOptionField::Type::kChoice,
          help,
          std::move(choices),
          [access](const LensOptions& o) { return to_string(access(o)); },
          [access, &names, name, listed](LensOptions& o, const std::string& text) {
            for (const EnumName<Enum>& entry : names)
              if (text == entry.name) {
                access(o) = entry.value;
                return;
              }
            throw InvalidOption("LensOptions", name, "must be " + listed + ", got '" + text + "'");
          }};
}

}  // namespace

const std::vector<LensOptionField>& lens_option_fields() {
  static const std::vector<LensOptionField> fields = {
      choice_field(
          "model",
          "focus (the region magnified as a whole, the context giving way within the "
          "footprint), lift (the paper's: lifted triangles, harmonic texture), field "
          "(the lift as a zoom field: any shape reaches its zoom at its peak) or auto "
          "(lift for circles only, else field)",
          kLensModels, [](auto& o) -> auto& { return o.model; }),
      integer_field(
          "mesh", "grid vertices along the long side, in [4, 1000]",
          [](auto& o) -> auto& { return o.mesh; }),
      number_field(
          "mesh_tolerance",
          "focus model: the grid is refined where the lens's start strays from linear "
          "over a triangle by more than this, output pixels, or 1/400 of the smallest "
          "lens's reach, >= 0 (0: not refined)",
          [](auto& o) -> auto& { return o.mesh_tolerance; }),
      integer_field(
          "draft_mesh",
          "a session's drafts (a drag's frames) on a grid of this many vertices along "
          "the long side (0: mesh; else in [4, 1000])",
          [](auto& o) -> auto& { return o.draft_mesh; }),
      integer_field(
          "subdivide",
          "bisection rounds refining triangles the lift stretches, in [0, 8] (0: none)",
          [](auto& o) -> auto& { return o.subdivision.max_levels; }),
      choice_field(
          "metric", "paper (Eq. 6 alpha blend) or spectrum (ARAP..ASAP)", kMetrics,
          [](auto& o) -> auto& { return o.flatten.metric; }),
      number_field(
          "alpha", "metric blend: paper [0, 1), spectrum [0, 1]",
          [](auto& o) -> auto& { return o.flatten.alpha; }),
      choice_field(
          "weights", "flattening weights of the lift model: paper or cotan", kFlattenWeights,
          [](auto& o) -> auto& { return o.flatten.weights; }),
      choice_field(
          "texture", "texture map weights of the lift model: cotan, cotan+ or mvc", kTextureWeights,
          [](auto& o) -> auto& { return o.texture; }),
      choice_field(
          "boundary", "image border: sliding, fixed or free", kBoundaries,
          [](auto& o) -> auto& { return o.flatten.boundary; }),
      choice_field(
          "extent", "global (the whole image gives way) or local (a patch around the lenses)",
          kExtents, [](auto& o) -> auto& { return o.extent; }),
      number_field(
          "extent_factor", "local patch half-side over the lens radius, in (1, 100]",
          [](auto& o) -> auto& { return o.extent_factor; }),
      number_field(
          "tolerance", "relative energy change that stops iterating",
          [](auto& o) -> auto& { return o.flatten.tolerance; }),
      integer_field(
          "max_iterations", "cap on flattening iterations",
          [](auto& o) -> auto& { return o.flatten.max_iterations; }),
      integer_field(
          "threads",
          "threads of the lens solve (and of magnify's rendering), >= 0 (0: all "
          "cores); the results do not depend on it",
          [](auto& o) -> auto& { return o.flatten.threads; }),
  };
  return fields;
}

const LensOptionField& lens_option_field(const std::string& name) {
  for (const LensOptionField& field : lens_option_fields())
    if (name == field.name) return field;
  std::string names;
  for (const LensOptionField& field : lens_option_fields())
    names += (names.empty() ? "" : ", ") + std::string(field.name);
  throw InvalidInput("lens_option_field: unknown option '" + name + "' (expected " + names + ")");
}

std::string option_flag(const std::string& name) {
  std::string flag = "--" + name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

}  // namespace geolens
