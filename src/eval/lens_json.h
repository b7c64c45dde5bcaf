#pragma once
// Private to eval/: one lens as JSON, the same object in a run's stats (run_stats.h) and in a
// comparison's report (comparison.h).

#include <nlohmann/json.hpp>

#include "geolens/eval/comparison.h"
#include "geolens/lens/geometric_lens.h"

namespace geolens {

/// The lens's region (`kind`, `bbox` [x0, y0, x1, y1], `peak` [x, y], `size`, and `center`
/// [x, y] and `radius` for a circle; pixels), `profile`, `zoom_requested`, `zoom_measured` (at
/// the peak, on the warp measured), `footprint` (the ratio, footprint_ratio), and what `focus`
/// measured on that warp: `focus` {`zoom`, `uniformity`, `shape_mean`, `shape_max`},
/// `footprint_radius` and `displacement_beyond_footprint` (pixels). `profile` and `footprint`
/// only where `model` (the one that solved the lens) reads them (reads_option).
nlohmann::json lens_json(const Lens& lens, double zoom_measured, const FocusMeasure& focus,
                         LensModel model);

}  // namespace geolens
