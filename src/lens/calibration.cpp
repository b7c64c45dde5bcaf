#include "lens/calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
// The fits are taken at most at zoom 8, where they still rise.
const double kLargestFittedLogZoom = std::log(8.0);
// Caps: the lift's height over size, and the field's (and a focus's) peak log zoom: at most 64x,
// the square of the largest zoom a lens may ask for (the context's resistance takes the rest).
constexpr double kMaxHeightOverSize = 20.0;
const double kMaxLogZoom = 2 * std::log(8.0);

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
  const size_t n = lenses.size();
  // Per lens, a bracket [lo, hi] of heights on f(h) = log(zoom(h)) - log(target), f(0) < 0,
  // refined by false position (Illinois variant: an end kept twice has its f halved).
  std::vector<double> lo(n, 0), hi(n, -1), f_lo(n), f_hi(n, 0);
  std::vector<int> last_side(n, 0);
  for (size_t k = 0; k < n; ++k) f_lo[k] = -std::log(lenses[k].zoom);
  StageTimings sum;
  LensResult best;
  double best_miss = std::numeric_limits<double>::infinity();
  for (int solve = 1;; ++solve) {
    LensResult r = run(h, solve);
    sum.lift += r.timings.lift;
    sum.texture += r.timings.texture;
    sum.factorize += r.timings.factorize;
    sum.iterate += r.timings.iterate;
    sum.total += r.timings.total;
    // Keep the solve whose worst lens is closest to its zoom, should calibration not converge.
    double miss = 0;
    for (size_t k = 0; k < n; ++k)
      miss = std::max(miss, std::abs(std::log(r.zoom_measured[k] / lenses[k].zoom)));
    bool done = true;
    for (size_t k = 0; k < n; ++k) {
      if (h[k] == 0) continue;
      const double gain = std::log(r.zoom_measured[k]);
      const double f = gain - std::log(lenses[k].zoom);
      if (std::abs(f) <= std::log1p(tolerance)) continue;
      done = false;
      const int side = f < 0 ? -1 : 1;
      if (side < 0) {
        lo[k] = h[k];
        f_lo[k] = f;
        if (last_side[k] < 0) f_hi[k] *= 0.5;
      } else {
        hi[k] = h[k];
        f_hi[k] = f;
        if (last_side[k] > 0) f_lo[k] *= 0.5;
      }
      last_side[k] = side;
      if (hi[k] < 0) {
        // No upper end yet: scale the height by the first guess's ratio between the zoom
        // wanted and the zoom reached (the guess's curve through h = 0), at most doubling.
        h[k] = gain > 0
                   ? std::min(2.0 * h[k], h[k] * height_for_zoom(lenses[k], model, lenses[k].zoom) /
                                              height_for_zoom(lenses[k], model, std::exp(gain)))
                   : 2.0 * h[k];
      } else {
        h[k] = lo[k] + (hi[k] - lo[k]) * f_lo[k] / (f_lo[k] - f_hi[k]);
      }
      h[k] = std::min(h[k], height_cap(lenses[k], model));
    }
    if (miss < best_miss) {
      best_miss = miss;
      best = std::move(r);
    }
    if (done || solve >= max_solves || model == LensModel::kFocus) {
      best.solves = solve;
      break;
    }
  }
  best.timings = sum;
  return best;
}

}  // namespace geolens
