#pragma once
// Private: the one loop that makes lenses' measured zooms meet their targets, for
// GeometricLens's calibration of bump heights (calibration.h) and match_classic_lens's zoom
// parameters (classic_lens.h).

#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace geolens {

/// Where one lens stands while no parameter beyond its root is known: the parameter just tried
/// and its residual (< 0: too little zoom), and the point tried before it (the identity, x = 0
/// with f = -log target, at first).
struct ZoomProbe {
  double x, f, x_before, f_before;
};

/// Per lens k, a parameter x_k >= 0 whose residual f_k(x) = log(measured_k / targets[k]) is
/// within log1p(tolerance) of 0, for parameters where x = 0 is the identity (f_k(0) =
/// -log targets[k]) and f_k grows with x. Starts at `x` (a lens at 0 keeps it: its target is 1).
/// Each round, `evaluate(x, round)` (round from 1) builds and measures every lens at once and
/// `measured(result, k)` reads lens k's zoom from it. While a lens has no parameter above its
/// root, its next one is `extrapolate(k, probe)`; then false position in the bracket (Illinois
/// variant: an end kept twice has its residual halved). Every parameter is kept in [0, cap(k)].
/// Stops when every lens meets its target, or after `max_rounds`; returns the round whose worst
/// lens was closest (its number of rounds in `rounds`).
template <class Result>
Result match_zooms(std::vector<double> x, const std::vector<double>& targets, double tolerance,
                   int max_rounds,
                   const std::function<Result(const std::vector<double>&, int)>& evaluate,
                   const std::function<double(const Result&, size_t)>& measured,
                   const std::function<double(size_t, const ZoomProbe&)>& extrapolate,
                   const std::function<double(size_t)>& cap, int& rounds) {
  const size_t n = targets.size();
  std::vector<double> lo(n, 0), hi(n, -1), f_lo(n), f_hi(n, 0);
  std::vector<int> last_side(n, 0);
  for (size_t k = 0; k < n; ++k) f_lo[k] = -std::log(targets[k]);
  Result best{};
  double best_miss = std::numeric_limits<double>::infinity();
  for (int round = 1;; ++round) {
    Result result = evaluate(x, round);
    double miss = 0;
    bool done = true;
    for (size_t k = 0; k < n; ++k) {
      const double f = std::log(measured(result, k) / targets[k]);
      miss = std::max(miss, std::abs(f));
      if (x[k] == 0 || std::abs(f) <= std::log1p(tolerance)) continue;
      done = false;
      const ZoomProbe probe{x[k], f, lo[k], f_lo[k]};
      const int side = f < 0 ? -1 : 1;
      if (side < 0) {
        lo[k] = x[k];
        f_lo[k] = f;
        if (last_side[k] < 0) f_hi[k] *= 0.5;
      } else {
        hi[k] = x[k];
        f_hi[k] = f;
        if (last_side[k] > 0) f_lo[k] *= 0.5;
      }
      last_side[k] = side;
      x[k] = hi[k] < 0 ? extrapolate(k, probe)
                       : lo[k] + (hi[k] - lo[k]) * f_lo[k] / (f_lo[k] - f_hi[k]);
      x[k] = std::clamp(x[k], 0.0, cap(k));
    }
    if (miss < best_miss) {
      best_miss = miss;
      best = std::move(result);
    }
    if (done || round >= max_rounds) {
      rounds = round;
      return best;
    }
  }
}

}  // namespace geolens
