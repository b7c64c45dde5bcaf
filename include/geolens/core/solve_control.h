#pragma once
// Following and stopping a long call (a lens solve) from another thread.

#include <atomic>
#include <functional>

namespace geolens {

/// Where a running solve is, as reported to SolveControl::progress.
struct SolveProgress {
  int solve = 0;      ///< calibration solve, from 1 (0 where the caller does not count them)
  int iteration = 0;  ///< global steps the flattening of this solve has taken, from 0
  double energy = 0;  ///< the flattening's energy after them, pixels^2
};

/// What a caller passes to a long call to follow it and to stop it; both parts are optional.
/// The call checks at every step of its flattening (a step takes about a millisecond at 100 x
/// 100 vertices, 5 - 10 at 200 x 200).
struct SolveControl {
  /// Set by any thread to stop the call: at its next step it throws Cancelled.
  const std::atomic<bool>* cancel = nullptr;
  /// Called on the solving thread after each step; must not call back into the solve.
  std::function<void(const SolveProgress&)> progress;

  /// Reports `p` to progress, then throws Cancelled("<function>: cancelled") if cancel is set.
  void step(const SolveProgress& p, const char* function) const;
};

}  // namespace geolens
