#pragma once
// The --stats JSON document of `geolens magnify`.

#include <nlohmann/json.hpp>
#include <vector>

#include "geolens/lens/geometric_lens.h"
#include "geolens/measure/distortion.h"

namespace geolens::cli {

/// Everything a user needs to judge one magnify run: mesh size, convergence, flips, per-lens
/// requested and measured zoom, distortion and stage timings (milliseconds).
nlohmann::json make_stats(const std::vector<Lens>& lenses, const LensOptions& options,
                          const LensResult& result, const DistortionSummary& distortion,
                          double render_ms, double total_ms);

}  // namespace geolens::cli
