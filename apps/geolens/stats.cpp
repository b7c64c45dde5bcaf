#include "stats.h"

namespace geolens::cli {

nlohmann::json make_stats(const std::vector<Lens>& lenses, const LensOptions& options,
                          const LensResult& result, const DistortionSummary& summary,
                          double render_ms, double total_ms) {
  nlohmann::json stats;
  stats["vertices"] = result.warp.source.rows();
  stats["triangles"] = result.warp.F.rows();
  stats["iterations"] = result.flattening.iterations;
  stats["converged"] = result.flattening.converged;
  stats["energy"] = result.flattening.energy;
  stats["calibration_solves"] = result.solves;
  stats["flipped"] = summary.flipped;
  stats["options"] = {{"mesh", options.mesh},
                      {"texture", to_string(options.texture)},
                      {"weights", to_string(options.flatten.weights)},
                      {"metric", to_string(options.flatten.metric)},
                      {"alpha", options.flatten.alpha},
                      {"boundary", to_string(options.flatten.boundary)},
                      {"tolerance", options.flatten.tolerance},
                      {"max_iterations", options.flatten.max_iterations}};
  nlohmann::json list = nlohmann::json::array();
  for (size_t k = 0; k < lenses.size(); ++k) {
    list.push_back({{"kind", "circle"},
                    {"center", {lenses[k].roi.center.x(), lenses[k].roi.center.y()}},
                    {"radius", lenses[k].roi.radius},
                    {"profile", to_string(lenses[k].profile)},
                    {"zoom_requested", lenses[k].zoom},
                    {"zoom_measured", result.zoom_measured[k]},
                    {"height", result.heights[k]}});
  }
  stats["lenses"] = list;
  stats["distortion"] = {{"conformal_mean", summary.conformal_mean},
                         {"conformal_max", summary.conformal_max}};
  stats["timings_ms"] = {{"lift", result.timings.lift},
                         {"texture", result.timings.texture},
                         {"factorize", result.timings.factorize},
                         {"iterate", result.timings.iterate},
                         {"render", render_ms},
                         {"total", total_ms}};
  return stats;
}

}  // namespace geolens::cli
