#pragma once
// A comparison (comparison.h) and a footprint sweep (footprint_sweep.h) as text: JSON (2-space
// indented, newline at the end) and Markdown, what `geolens compare` writes.

#include <string>

#include "geolens/eval/comparison.h"
#include "geolens/eval/footprint_sweep.h"

namespace geolens {

/// {"methods": [...]}, one object per method in order: `name`, `zoom_center` (zoom_measured[0]),
/// `focus_uniformity` (the largest over the lenses of `focus.uniformity` below: over the region
/// given), `distortion` {`focus`, `transition`,
/// `context`, `overall`: {`mean`, `max`} shape distortion, null in a zone with no triangle},
/// `occluded_percent`, `flipped`, and `lenses`: per lens the same object as run_stats_json's
/// lenses without `height` and `zoom_fit` (`kind`, `bbox`, `peak`, `size`, `center` and
/// `radius` for circles, `profile`, `zoom_requested`, `zoom_measured` on this method's warp,
/// `footprint`, `focus` {`zoom`, `uniformity`, `shape_mean`, `shape_max`}, `footprint_radius`,
/// `displacement_beyond_footprint`).
std::string comparison_json(const Comparison& comparison);

/// The same as Markdown under the heading "# geolens compare: `title`" (the input's name): per
/// lens its disk and zooms, the shape distortion per zone, the area distortion per zone, the
/// per-lens focus measures, and the geometric lens's Eq. 7 energy.
std::string comparison_markdown(const Comparison& comparison, const std::string& title);

/// {"points": [...]}, per point of the sweep (in its order): `method`, `ratio`, `zoom`,
/// `uniformity`, `shape_max`, `footprint_radius` and the ratio's `bound`.
std::string sweep_json(const Sweep& sweep);

/// The sweep as a Markdown table under "# geolens compare --sweep: `title`": per ratio the zoom
/// the geometric lens reached, the bound, and each method's largest shape distortion (its focus
/// uniformity in brackets where above 1.01). Throws InvalidInput if a ratio has no "geometric"
/// point.
std::string sweep_markdown(const Sweep& sweep, const std::string& title);

}  // namespace geolens
