#include "lens/calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "lens/zoom_match.h"

namespace geolens {

namespace {

// The fitted constants, all of them.
//
// kLift: the calibrated peak height over the region's size is a L + b L^2 with L = log(zoom),
// per profile (gaussian, sphere, mesa), fitted through the calibrated heights of zoom 2 and 3
// (default options, 100 x 100 grid, r = 150 px on 1024 px, cell / r = 0.069), so those need a
// single solve.
constexpr double kLiftA[] = {1.180, 2.854, 2.264}, kLiftB[] = {-0.0912, -0.687, -0.453};
constexpr double kLiftFitCell = 0.069;
// The gaussian's peak is sharp, so a coarse grid under-represents its bump: the calibrated h0 / r
// for zoom 2 is 0.722 (cell / r below 0.035), 0.774 (0.069), 0.94 (0.138), about
// 1 + 15 (cell / r)^2 times the first.
constexpr double kGaussianCoarseness = 15;
// kField: the height over size is the peak's log zoom, which the context's resistance lowers by
// about 1 / 1.7.
constexpr double kFieldResistance = 1.7;
// The fits are taken at most at the largest zoom a lens may ask for, where they still rise.
const double kLargestFittedLogZoom = std::log(kMaxZoom);
// Caps: the lift's height over size, and the field's (and a focus's) peak log zoom: at most 64x,
// the square of the largest zoom a lens may ask for (the context's resistance takes the rest).
constexpr double kMaxHeightOverSize = 20.0;
const double kMaxLogZoom = 2 * std::log(kMaxZoom);

// The guess's curve through h = 0: the height the fits give for a zoom, before the grid's
// correction.
double height_for_zoom(const Lens& lens, LensModel model, double zoom) {
  if (model == LensModel::kFocus) return std::log(zoom);  // exact, up to the focus weight
  const double L = std::min(std::log(zoom), kLargestFittedLogZoom);
  if (model == LensModel::kField) return lens.region.size() * kFieldResistance * L;
  const int p = int(lens.profile);
  return lens.region.size() * (kLiftA[p] * L + kLiftB[p] * L * L);
}

// The largest height calibration tries (a taller bump only folds).
double height_cap(const Lens& lens, LensModel model) {
  if (model == LensModel::kFocus) return kMaxLogZoom;
  return lens.region.size() * (model == LensModel::kField ? kMaxLogZoom : kMaxHeightOverSize);
}

}  // namespace

double initial_height(const Lens& lens, LensModel model, double cell) {
  const double h = height_for_zoom(lens, model, lens.zoom);
  if (model != LensModel::kLift || lens.profile != Profile::kGaussian) return h;
  auto coarseness = [](double x) { return 1 + kGaussianCoarseness * x * x; };
  return h * coarseness(cell / lens.region.size()) / coarseness(kLiftFitCell);
}

LensResult calibrate(const std::vector<Lens>& lenses, LensModel model, std::vector<double> h,
                     double tolerance, int max_solves,
                     const std::function<LensResult(const std::vector<double>&, int)>& run) {
  std::vector<double> targets;
  for (const Lens& lens : lenses) targets.push_back(lens.zoom);
  StageTimings sum;
  int solves = 0;
  LensResult best = match_zooms<LensResult>(
      std::move(h), targets, tolerance,
      // A focus lens's zoom is its focus's scale, not a result to aim for: one solve.
      model == LensModel::kFocus ? 1 : max_solves,
      [&](const std::vector<double>& heights, int solve) {
        LensResult r = run(heights, solve);
        sum.lift += r.timings.lift;
        sum.texture += r.timings.texture;
        sum.factorize += r.timings.factorize;
        sum.iterate += r.timings.iterate;
        sum.total += r.timings.total;
        return r;
      },
      [](const LensResult& r, size_t k) { return r.zoom_measured[k]; },
      // No height known above the root: scale the height by the first guess's ratio between the
      // zoom wanted and the zoom reached (the guess's curve through h = 0), at most doubling.
      [&](size_t k, const ZoomProbe& p) {
        const double gain = p.f + std::log(targets[k]);
        if (gain <= 0) return 2.0 * p.x;
        return std::min(2.0 * p.x, p.x * height_for_zoom(lenses[k], model, targets[k]) /
                                       height_for_zoom(lenses[k], model, std::exp(gain)));
      },
      [&](size_t k) { return height_cap(lenses[k], model); }, solves);
  best.solves = solves;
  best.timings = sum;
  return best;
}

}  // namespace geolens
