// The options a model does not read (unread_options) against the solver itself: an option is
// listed exactly when setting it leaves the warp unchanged, for every model and both kinds of
// region.

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_options.h"

namespace geolens {
namespace {

constexpr double kWidth = 200, kHeight = 160;

using Setup = std::function<void(LensOptions&, std::vector<Lens>&)>;

// One option changed from `before` (applied to both solves) by `change`.
struct Variant {
  std::string option;
  Setup before, change;
};

std::vector<Variant> variants() {
  const Setup none = [](LensOptions&, std::vector<Lens>&) {};
  return {
      {"profile", none,
       [](LensOptions&, std::vector<Lens>& l) { l[0].profile = Profile::kSphere; }},
      {"footprint", none, [](LensOptions&, std::vector<Lens>& l) { l[0].footprint = 6; }},
      {"mesh_tolerance", none, [](LensOptions& o, std::vector<Lens>&) { o.mesh_tolerance = 0.02; }},
      {"subdivide", none, [](LensOptions& o, std::vector<Lens>&) { o.subdivision.max_levels = 2; }},
      {"extent", none, [](LensOptions& o, std::vector<Lens>&) { o.extent = Extent::kLocal; }},
      {"extent_factor", none, [](LensOptions& o, std::vector<Lens>&) { o.extent_factor = 1.5; }},
      {"extent_factor", [](LensOptions& o, std::vector<Lens>&) { o.extent = Extent::kLocal; },
       [](LensOptions& o, std::vector<Lens>&) { o.extent_factor = 1.5; }},
      {"texture", none,
       [](LensOptions& o, std::vector<Lens>&) { o.texture = TextureWeights::kMeanValue; }},
      {"weights", none,
       [](LensOptions& o, std::vector<Lens>&) { o.flatten.weights = FlattenWeights::kCotan; }},
      {"metric", none,
       [](LensOptions& o, std::vector<Lens>&) { o.flatten.metric = Metric::kSpectrum; }},
      {"metric", [](LensOptions& o, std::vector<Lens>&) { o.flatten.alpha = 0.5; },
       [](LensOptions& o, std::vector<Lens>&) { o.flatten.metric = Metric::kSpectrum; }},
      {"alpha", none, [](LensOptions& o, std::vector<Lens>&) { o.flatten.alpha = 0.5; }},
      {"boundary", none,
       [](LensOptions& o, std::vector<Lens>&) { o.flatten.boundary = Boundary::kFixed; }},
  };
}

// (Eigen's == needs equal sizes: a refined mesh may have other counts.)
bool same_warp(const LensResult& a, const LensResult& b) {
  return a.warp.F.rows() == b.warp.F.rows() && a.warp.screen.rows() == b.warp.screen.rows() &&
         a.warp.F == b.warp.F && a.warp.screen == b.warp.screen && a.warp.source == b.warp.source;
}

class UnreadOptions : public testing::TestWithParam<LensModel> {};

TEST_P(UnreadOptions, ListedExactlyWhenTheWarpIgnoresThem) {
  const Region regions[] = {
      Region::circle({90, 80}, 25),
      Region::polygon({{70, 60}, {120, 65}, {115, 100}, {75, 95}}),
  };
  for (const Region& region : regions) {
    for (const Variant& v : variants()) {
      LensOptions options;
      options.model = GetParam();
      options.mesh = 30;
      options.flatten.tolerance = 0.05;  // stopped early, where alpha and metric show
      std::vector<Lens> lenses{{region, 2.5}};
      v.before(options, lenses);
      const LensResult base = GeometricLens(kWidth, kHeight, options).solve(lenses);
      v.change(options, lenses);
      const LensResult changed = GeometricLens(kWidth, kHeight, options).solve(lenses);
      const std::vector<UnreadOption> unread = unread_options(options, lenses);
      const bool listed = std::any_of(unread.begin(), unread.end(),
                                      [&](const UnreadOption& u) { return u.name == v.option; });
      EXPECT_EQ(listed, same_warp(base, changed))
          << v.option << " with the " << to_string(GetParam()) << " model on a " << region.kind();
      EXPECT_EQ(listed, !reads_option(options, lenses, v.option)) << v.option;
      // Nothing is listed at the defaults.
      LensOptions defaults;
      defaults.model = GetParam();
      EXPECT_TRUE(unread_options(defaults, {{region, 2.5}}).empty());
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Models, UnreadOptions,
                         testing::Values(LensModel::kFocus, LensModel::kLift, LensModel::kField,
                                         LensModel::kAuto),
                         [](const testing::TestParamInfo<LensModel>& info) {
                           return to_string(info.param);
                         });

}  // namespace
}  // namespace geolens
