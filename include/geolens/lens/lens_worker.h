#pragma once
// A LensSession on its own thread, for a UI loop that must not wait for a solve.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geolens/core/solve_control.h"
#include "geolens/lens/lens_method.h"
#include "geolens/lens/lens_session.h"

namespace geolens {

/// What a LensWorker runs for each request: solves `lenses`, checking `control` where it can,
/// and returns the result (any lens method's Magnification; a LensSession's is a LensResult).
using LensJob = std::function<std::shared_ptr<const Magnification>(const std::vector<Lens>&,
                                                                   const SolveControl&)>;

/// A LensJob that runs `method` on a width x height source (it cannot be stopped midway; a
/// cancelled request's answer is dropped).
LensJob method_job(std::shared_ptr<const LensMethod> method, double width, double height);

/// What the worker has to show: the latest result it finished, and the latest error.
struct LensFrame {
  std::uint64_t request = 0;                    ///< the request `result` answers; 0: none yet
  std::shared_ptr<const Magnification> result;  ///< null before the first success
  double solve_ms = 0;                          ///< wall-clock time of that solve, milliseconds
  /// The latest request that failed (InvalidInput, SolverError) after `request`, and why; 0 and
  /// empty if none did.
  std::uint64_t failed_request = 0;
  std::string error;  ///< the failed request's message, as the exception's what() said it
};

/// Runs a LensSession (or any lens method) on a worker thread. The UI thread submits the lenses
/// of each frame and draws latest() meanwhile; only the newest request waits (one submitted
/// while another waits replaces it), so the worker never falls behind the pointer. Every call
/// is thread-safe.
class LensWorker {
 public:
  /// How long a draft stays before its full frame is solved: a pointer's moves come every
  /// frame while it drags (16 - 40 ms apart), so this is a pause, not a drag.
  static constexpr std::chrono::milliseconds kSettle{50};

  /// The geometric lens, frame after frame (its results are LensResults): each request is
  /// solved as a draft first (LensSession::update), then, once no other request has come for
  /// `settle`, in full (a request submitted during that full solve stops it). So a drag shows
  /// drafts at a draft's pace, none of its time spent on full frames it would drop, and the
  /// lens at rest its full frame. `progress` (optional) is called on the worker thread during
  /// each solve.
  explicit LensWorker(LensSession session,
                      std::function<void(const SolveProgress&)> progress = nullptr,
                      std::chrono::milliseconds settle = kSettle);
  /// Any job, e.g. method_job(a ClassicMethod).
  explicit LensWorker(LensJob job, std::function<void(const SolveProgress&)> progress = nullptr);
  /// Stops the solve under way and joins the thread.
  ~LensWorker();
  LensWorker(const LensWorker&) = delete;
  LensWorker& operator=(const LensWorker&) = delete;

  /// Asks for `lenses` to be solved; returns the request's number (1, 2, ...).
  std::uint64_t submit(std::vector<Lens> lenses);
  /// Stops the solve under way (its request is dropped; latest() keeps the one before) and drops
  /// the waiting request.
  void cancel();
  /// The latest finished frame (a copy; the result is shared and immutable).
  LensFrame latest() const;
  /// Blocks until no request is waiting or being solved.
  void wait_idle();
  /// Blocks until request `request` (or a later one) is answered or has failed, at most
  /// `timeout` (less if the worker goes idle without it: cancelled); returns whether it was. A UI
  /// that waits a few milliseconds after submitting shows a fast answer in the same frame.
  bool wait_for(std::uint64_t request, std::chrono::milliseconds timeout);

 private:
  struct Impl;  // the jobs, their NewestWorker and the latest frame (lens_worker.cpp)
  std::unique_ptr<Impl> impl_;
};

}  // namespace geolens
