#pragma once
// Private: a root of a continuous function on a bracket, by the Illinois variant of regula falsi
// (Dowell and Jarratt 1971), which converges superlinearly on smooth functions and never leaves
// the bracket.

#include <cmath>
#include <utility>

namespace geolens {

/// A t in [lo, hi] where f changes sign, f(lo) and f(hi) of opposite signs (or one of them 0):
/// the bracket is narrowed until it is within `tolerance` (in t) or 100 steps; returns the end
/// whose value is nearer 0.
template <class F>
double bracketed_root(const F& f, double lo, double hi, double tolerance) {
  double f_lo = f(lo), f_hi = f(hi);
  if (f_lo == 0) return lo;
  if (f_hi == 0) return hi;
  int kept = 0;  // which end stayed in the last step: -1 lo, 1 hi
  for (int step = 0; step < 100 && hi - lo > tolerance; ++step) {
    double t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);  // rounding: bisect
    const double f_t = f(t);
    if (f_t == 0) return t;
    if ((f_t < 0) == (f_lo < 0)) {
      lo = t, f_lo = f_t;
      if (kept == 1) f_hi *= 0.5;  // hi stayed twice: halve its weight (Illinois)
      kept = 1;
    } else {
      hi = t, f_hi = f_t;
      if (kept == -1) f_lo *= 0.5;
      kept = -1;
    }
  }
  return std::abs(f_lo) <= std::abs(f_hi) ? lo : hi;
}

}  // namespace geolens
