#pragma once
// The viewer's solves, off the UI thread, through the library's LensWorker: the geometric lens
// (a LensSession) or a classic lens (ClassicMethod, method_job). The UI thread submits the lenses
// of a frame and draws the latest finished answer meanwhile.

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_method.h"
#include "geolens/lens/lens_worker.h"

namespace geolens::view {

/// "geometric", then every classic lens's name (to_string(ClassicLens)).
std::vector<std::string> method_names();
bool is_method_name(const std::string& name);
/// The names joined by ", ", for messages.
std::string method_list();

/// What the solver has to show.
struct SolvedFrame {
  std::uint64_t request = 0;                    ///< the request answered; 0: none yet
  std::shared_ptr<const Magnification> result;  ///< null before the first answer
  std::vector<Lens> lenses;                     ///< the lenses `result` was solved for
  double solve_ms = 0;                          ///< wall-clock time of that solve, milliseconds
  /// The geometric lens's stages of that solve (LensResult::timings, summed over its `solves`
  /// calibration solves); none for a classic lens, which has no stages, or the identity.
  std::optional<StageTimings> stages;
  int solves = 0;
  std::string error;  ///< why the latest request after `request` failed; empty if none did
};

/// One method on a width x height source, solved off the calling thread. An empty lens list is
/// answered at once with the identity (no lens method takes one).
class LensSolver {
 public:
  /// `method` one of method_names(); `options` the geometric lens's (its mesh also sets the
  /// classic lens's grid). Throws InvalidInput for an unknown method or invalid options.
  LensSolver(int width, int height, const std::string& method, const LensOptions& options);

  /// Asks for `lenses` to be solved. With `drop_stale` the solve under way and the waiting
  /// request are dropped first (an edit that makes them useless: a lens added, removed or
  /// re-zoomed); without it (a drag) the solve under way finishes and only the newest request
  /// waits, so a steady drag keeps showing frames. Returns the request's number.
  std::uint64_t submit(const std::vector<Lens>& lenses, bool drop_stale);
  SolvedFrame latest() const;  ///< the latest answer; cheap, for every frame
  void wait_idle();            ///< blocks until every request is answered
  const std::string& method() const { return method_; }
  const LensOptions& options() const { return options_; }

 private:
  int width_, height_;
  std::string method_;
  LensOptions options_;
  std::unique_ptr<LensWorker> worker_;  // a LensSession's, or a classic lens's method_job
  // Each request not answered yet, by the worker's request number: its own number and lenses.
  // Dropped requests leave the map, so their late answers are never shown.
  struct Pending {
    std::uint64_t request;
    std::vector<Lens> lenses;
  };
  mutable std::mutex mutex_;
  mutable std::map<std::uint64_t, Pending> pending_;
  mutable SolvedFrame shown_;
  std::uint64_t submitted_ = 0;
};

}  // namespace geolens::view
