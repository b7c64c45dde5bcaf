#include <algorithm>

#include "geolens/lens/lens_options.h"

namespace geolens {
namespace {

constexpr const char* kNames[] = {"profile", "footprint",     "mesh_tolerance", "subdivide",
                                  "extent",  "extent_factor", "texture",        "weights",
                                  "metric",  "alpha",         "boundary"};

// Whether `model` reads option `name` with the options `o`, and if not, why.
struct Use {
  bool read;
  const char* reason;
};
Use use(const std::string& name, LensModel model, const LensOptions& o) {
  const bool focus = model == LensModel::kFocus, lift = model == LensModel::kLift;
  constexpr const char* kBounded = "the focus model bounds the context's distortion itself";
  constexpr const char* kFootprints = "the focus model solves its footprints only";
  if (name == "profile")
    return {!focus,
            "the focus model magnifies the region uniformly; the profile shapes the lift's bump"};
  if (name == "footprint") return {focus, "only the focus model has a footprint"};
  if (name == "mesh_tolerance") return {focus, "only the focus model refines its mesh"};
  if (name == "subdivide") return {!focus, "only the lift and field models subdivide their mesh"};
  if (name == "extent") return {!focus, kFootprints};
  if (name == "extent_factor")
    return {!focus && o.extent == Extent::kLocal,
            focus ? kFootprints : "it sizes the local extent only"};
  if (name == "texture") return {lift, "only the lift model re-maps the texture"};
  if (name == "weights")
    return {lift, "only the lift model flattens with other than cotan weights"};
  if (name == "metric")
    return {!focus && o.flatten.alpha > 0,
            focus ? kBounded : "at alpha 0 both metrics are as-rigid-as-possible"};
  if (name == "alpha") return {!focus, kBounded};
  if (name == "boundary") return {!focus, "the focus model slides the image's sides"};
  return {true, ""};  // read by every model
}

// Whether `name` differs from its default in `o` (its text in the table of fields) or in any of
// `lenses` (profile, footprint).
bool is_set(const std::string& name, const LensOptions& o, const std::vector<Lens>& lenses) {
  const Lens l{Region::circle(Eigen::Vector2d::Zero(), 1)};  // its defaults
  auto any_lens = [&](auto differs) { return std::any_of(lenses.begin(), lenses.end(), differs); };
  if (name == "profile") return any_lens([&](const Lens& k) { return k.profile != l.profile; });
  if (name == "footprint")
    return any_lens([&](const Lens& k) { return k.footprint != l.footprint; });
  const LensOptionField& field = lens_option_field(name);
  return field.get(o) != field.get(LensOptions{});
}

}  // namespace

bool reads_option(const LensOptions& options, const std::vector<Lens>& lenses,
                  const std::string& name) {
  return use(name, resolved_model(options.model, lenses), options).read;
}

std::vector<UnreadOption> unread_options(const LensOptions& options,
                                         const std::vector<Lens>& lenses) {
  const LensModel model = resolved_model(options.model, lenses);
  std::vector<UnreadOption> unread;
  for (const char* name : kNames) {
    const Use u = use(name, model, options);
    if (!u.read && is_set(name, options, lenses)) unread.push_back({name, u.reason});
  }
  return unread;
}

}  // namespace geolens
