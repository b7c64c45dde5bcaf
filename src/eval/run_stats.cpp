#include "geolens/eval/run_stats.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "eval/lens_json.h"
#include "geolens/eval/comparison.h"
#include "geolens/lens/lens_options.h"

namespace geolens {

std::string run_stats_json(const std::vector<Lens>& lenses, const LensOptions& options,
                           const LensResult& result, const DistortionSummary& summary,
                           const RunTimings& timings, const RunSource& source) {
  nlohmann::json stats;
  stats["vertices"] = result.warp.source.rows();
  stats["triangles"] = result.warp.F.rows();
  stats["iterations"] = result.flattening.iterations;
  stats["converged"] = result.flattening.converged;
  stats["energy"] = result.flattening.energy;
  stats["calibration_solves"] = result.solves;
  stats["bounded_steps"] = result.flattening.bounded_steps;
  stats["texture_fallback"] = result.texture_fallback;
  stats["flipped"] = summary.flipped;
  stats["model"] = to_string(result.model);
  // Only what the model read: an option it does not (lens_options.h) is left out.
  nlohmann::json& echoed = stats["options"];
  echoed = {{"mesh", options.mesh},
            {"model", to_string(options.model)},
            {"mesh_tolerance", options.mesh_tolerance},
            {"subdivide", options.subdivision.max_levels},
            {"extent", to_string(options.extent)},
            {"extent_factor", options.extent_factor},
            {"texture", to_string(options.texture)},
            {"weights", to_string(options.flatten.weights)},
            {"metric", to_string(options.flatten.metric)},
            {"alpha", options.flatten.alpha},
            {"boundary", to_string(options.flatten.boundary)},
            {"tolerance", options.flatten.tolerance},
            {"max_iterations", options.flatten.max_iterations}};
  for (auto it = echoed.begin(); it != echoed.end();)
    it = reads_option(options, lenses, it.key()) ? std::next(it) : echoed.erase(it);
  const std::vector<FocusMeasure> foci =
      measure_foci(result.warp, measure_triangles(result.warp), lenses);
  nlohmann::json list = nlohmann::json::array();
  for (size_t k = 0; k < lenses.size(); ++k) {
    nlohmann::json lens = lens_json(lenses[k], result.zoom_measured[k], foci[k], result.model);
    if (k < result.lift_heights_px.size()) lens["height"] = result.lift_heights_px[k];
    if (k < result.zoom_fits.size()) lens["zoom_fit"] = result.zoom_fits[k];
    if (k < result.zoom_fit_reasons.size()) lens["zoom_fit_reason"] = result.zoom_fit_reasons[k];
    list.push_back(lens);
  }
  stats["lenses"] = list;
  stats["distortion"] = {{"conformal_mean", summary.conformal_mean},
                         {"conformal_max", summary.conformal_max},
                         {"degenerate", summary.degenerate()}};
  const double parts =
      timings.load + result.timings.total + timings.measure + timings.render + timings.save;
  stats["timings_ms"] = {{"load", timings.load},
                         {"lift", result.timings.lift},
                         {"texture", result.timings.texture},
                         {"factorize", result.timings.factorize},
                         {"iterate", result.timings.iterate},
                         {"solve", result.timings.total},
                         {"measure", timings.measure},
                         {"render", timings.render},
                         {"save", timings.save},
                         {"other", std::max(0.0, timings.total - parts)},
                         {"total", std::max(timings.total, parts)}};
  if (!source.kind.empty()) {
    nlohmann::json& entry = stats["source"];
    entry = {{"kind", source.kind},
             {"frame", {source.frame_width, source.frame_height}},
             {"scale", source.scale}};
    for (const auto& [name, value] : source.counters) entry[name] = value;
  }
  return stats.dump(2) + "\n";
}

}  // namespace geolens
