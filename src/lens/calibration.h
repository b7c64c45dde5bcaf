#pragma once
// Private: the zoom calibration of GeometricLens (docs/design.md, "Zoom calibration"): the first
// guess of each lens's peak height, with every fitted constant the library uses for it, and the
// loop that refines the heights until each lens's measured zoom meets its request.

#include <functional>
#include <vector>

#include "geolens/lens/geometric_lens.h"

namespace geolens {

/// First guess of the peak height for lens.zoom on a grid of cell side `cell` (pixels): exact
/// for kFocus (the log zoom), fitted for kLift and kField (calibration.cpp). Pixels, or log zoom
/// for kFocus.
double initial_height(const Lens& lens, LensModel model, double cell);

/// Refines the heights `h` (one per lens, 0 for a lens of zoom 1, which keeps it) by false
/// position on log(measured zoom / asked zoom), solving with `run`, until every lens is within
/// `tolerance` (relative) of its zoom or `max_solves` solves were made; kFocus takes one solve
/// (its zoom is its focus's scale, not a result to aim for). `run(heights, solve)` solves with
/// the heights (`solve` counts from 1) and fills zoom_measured. Returns the solve whose worst lens
/// was closest, with `solves` and the timings summed over all solves.
LensResult calibrate(const std::vector<Lens>& lenses, LensModel model, std::vector<double> h,
                     double tolerance, int max_solves,
                     const std::function<LensResult(const std::vector<double>&, int)>& run);

}  // namespace geolens
