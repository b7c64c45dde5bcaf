#pragma once
// Following and stopping a long call (a lens solve) from another thread, and running such calls
// off the calling thread, the newest first.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>

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

/// Runs jobs on a thread of its own, one at a time, the newest first: a job submitted while
/// another waits replaces it (the one replaced never runs), so a UI loop that submits every frame
/// never falls behind. What the lens worker (LensWorker) and the viewer's renders and file opens
/// run on. Every member is thread-safe; a job runs on the worker's thread only, and its exceptions
/// must stay inside it.
class NewestWorker {
  struct Impl;  // the thread, the waiting job and the flags (solve_control.cpp)

 public:
  /// What a job is given on the worker's thread: its request and the means to be stopped.
  class Run {
   public:
    std::uint64_t request() const { return request_; }  ///< from 1, as submit() returned it
    /// Set when the job should stop: cancel(), the worker destroyed, or, after
    /// cancel_on_newer(), a newer job submitted. A job that cannot stop midway may ignore it.
    const std::atomic<bool>& cancelled() const;
    /// Waits at most `quiet` for a newer job (or a cancel); returns whether none came.
    bool quiet_for(std::chrono::milliseconds quiet) const;
    /// From now on a newer job submitted sets cancelled() (work no longer worth finishing).
    void cancel_on_newer();
    /// Marks the request answered: wait_for(request()) returns true from now on.
    void answered();

   private:
    friend class NewestWorker;
    Impl* worker_ = nullptr;
    std::uint64_t request_ = 0;
  };
  /// A job: runs once on the worker's thread, given its Run.
  using Job = std::function<void(Run&)>;

  NewestWorker();
  /// Cancels the job under way (Run::cancelled), waits for it to return and joins the thread.
  ~NewestWorker();
  NewestWorker(const NewestWorker&) = delete;
  NewestWorker& operator=(const NewestWorker&) = delete;

  /// Asks for `job` to run; returns its request's number (1, 2, ...). Throws InvalidInput if
  /// `job` is empty.
  std::uint64_t submit(Job job);
  /// Drops the waiting job and cancels the one under way.
  void cancel();
  /// Blocks until no job is waiting or running.
  void wait_idle();
  /// Blocks until request `request` (or a later one) is answered (Run::answered), at most
  /// `timeout`, less if the worker goes idle without it; returns whether it was.
  bool wait_for(std::uint64_t request, std::chrono::milliseconds timeout);

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace geolens
