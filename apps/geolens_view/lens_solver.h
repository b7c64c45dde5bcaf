#pragma once
// The viewer's work off the UI thread: its solves, through the library's LensWorker (the
// geometric lens, a LensSession, or a classic lens, ClassicMethod, method_job), the pictures
// of a source finer than its frame rendered at the resolution they are shown (DetailWorker), and
// the frames of the files it opens and the views of a 3D scene it turns (SourceOpener). The
// UI thread submits requests and draws the latest finished answer meanwhile.

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "geolens/core/solve_control.h"
#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_method.h"
#include "geolens/lens/lens_worker.h"
#include "geolens/render/render.h"
#include "geolens/source/source_file.h"

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
  /// Per lens, what limits its zoom where it gets less than asked (LensResult::zoom_fit_reasons);
  /// empty for a classic lens.
  std::vector<std::string> fit_reasons;
  std::string error;  ///< why the latest request after `request` failed; empty if none did
};

/// One method on a width x height source, solved off the calling thread. An empty lens list is
/// answered at once with the identity (no lens method takes one).
class LensSolver {
 public:
  /// The geometric lens's drafts, a drag's frames, on a grid of at most this many vertices
  /// (LensOptions::draft_mesh, unless the options set one).
  static constexpr int kDraftMesh = 50;

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
  /// Blocks until the last request submitted is answered, at most `timeout`.
  void wait_for_last(std::chrono::milliseconds timeout);
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
  mutable std::uint64_t shown_worker_request_ = 0;  // the worker's request shown_ answers
  std::uint64_t submitted_ = 0;
};

/// Where a solved warp is shown in the window: the warp's screen point s (frame pixels) at window
/// pixel origin + s * scale, and the window pixels its picture covers.
struct DetailView {
  std::uint64_t frame = 0;  ///< the viewer's frame generation of the warp
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double scale = 1;  ///< window pixels per frame pixel
  int x = 0, y = 0;  ///< the covered window pixels: [x, x + width) x [y, y + height)
  int width = 0, height = 0;
  bool operator==(const DetailView& o) const {
    return frame == o.frame && origin == o.origin && scale == o.scale && x == o.x && y == o.y &&
           width == o.width && height == o.height;
  }
};

/// A warp rendered from a source file for a DetailView: `image` covers the view's window pixels
/// (x, y, width, height), at most kMaxSide texels a side (so a texel per window pixel unless the
/// view is larger).
struct DetailPicture {
  static constexpr int kMaxSide = 4096;
  DetailView view;
  Image image;
  double render_ms = 0;  ///< wall-clock time of the render, milliseconds
};

/// The viewer's jobs that take long (a render, a file opened) on the library's NewestWorker, with
/// their answers kept: only the newest request waits (one submitted while another waits replaces
/// it); a job under way cannot stop midway, and its answer is kept all the same: the caller tells
/// by the request's number whether an answer is the one it asked for last. `work` runs on the
/// worker's thread only, and its exceptions must stay inside it.
template <class Request, class Answer>
class NewestAnswers {
 public:
  /// An answer and the number of the request it answers (from 1), and how long `work` took.
  struct Done {
    std::uint64_t request = 0;
    Answer answer;
    double ms = 0;  ///< wall-clock time, milliseconds
  };

  explicit NewestAnswers(std::function<Answer(const Request&)> work) : work_(std::move(work)) {}

  /// Asks for work(request); returns the request's number.
  std::uint64_t submit(Request request) {
    return worker_.submit([this, request = std::move(request)](NewestWorker::Run& run) {
      auto done = std::make_shared<Done>();
      done->request = run.request();
      const auto start = std::chrono::steady_clock::now();
      done->answer = work_(request);
      done->ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count();
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = std::move(done);
    });
  }
  /// The latest finished answer (null before the first).
  std::shared_ptr<const Done> latest() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return done_;
  }
  /// Blocks until no request is waiting or being worked on.
  void wait_idle() { worker_.wait_idle(); }

 private:
  const std::function<Answer(const Request&)> work_;
  mutable std::mutex mutex_;
  std::shared_ptr<const Done> done_;
  NewestWorker worker_;  // last: its thread joined before the members above go
};

/// Renders warps from `file` (render(warp, file, options), source_file.h: its finer levels and
/// its overlay, such as a map's labels) on a NewestAnswers: the caller shows a picture only for
/// the view it asked it for.
class DetailWorker {
 public:
  explicit DetailWorker(std::shared_ptr<const SourceFile> file);

  /// Asks for `warp` (source and screen in frame pixels) shown as `view` says.
  void submit(std::shared_ptr<const Magnification> warp, const DetailView& view) {
    worker_.submit({std::move(warp), view});
  }
  /// The latest picture rendered (null before the first), and why the latest render failed
  /// (empty if it did not).
  std::shared_ptr<const DetailPicture> latest() const;
  std::string error() const;
  void wait_idle() { worker_.wait_idle(); }  ///< until no request is waiting or being rendered

 private:
  struct Request {
    std::shared_ptr<const Magnification> warp;
    DetailView view;
  };
  struct Answer {
    std::shared_ptr<const DetailPicture> picture;  // the latest rendered, even if this one failed
    std::string error;
  };
  NewestAnswers<Request, Answer> worker_;
};

/// A source file opened and its whole frame rendered at zoom 1 (what the viewer shows of it).
struct OpenedSource {
  std::string path;
  std::string kind;  ///< SourceFile::kind
  Image image;       ///< the frame: a pyramid's level 0 as it is, else rendered with its overlay
  /// The file, when it has detail finer than its frame (scale > 1, not a pyramid); else null.
  std::shared_ptr<const SourceFile> detail;
};

/// Opens `path` with `options` (open_source) and renders its frame as above. Throws as
/// open_source and render do.
OpenedSource open_frame(const std::string& path, const SourceFileOptions& options);

/// open_frame on a NewestAnswers: the caller shows an answer only for the request it asked last.
class SourceOpener {
 public:
  SourceOpener();

  struct Answer {
    std::uint64_t request = 0;
    std::optional<OpenedSource> opened;  ///< none when it failed
    std::string error;                   ///< why it failed (the exception's message)
    double ms = 0;                       ///< wall-clock time of open_frame, milliseconds
  };
  /// Asks for open_frame(path, options); returns the request's number (from 1).
  std::uint64_t submit(const std::string& path, const SourceFileOptions& options) {
    return worker_.submit({path, options});
  }
  /// The latest finished answer, once (then none until the next one finishes). UI thread only.
  std::optional<Answer> take();
  void wait_idle() { worker_.wait_idle(); }  ///< until no request is waiting or being opened

 private:
  struct Request {
    std::string path;
    SourceFileOptions options;
  };
  struct Opened {
    std::optional<OpenedSource> opened;
    std::string error;
  };
  NewestAnswers<Request, Opened> worker_;
  std::uint64_t taken_ = 0;  // the request of the answer taken last
};

}  // namespace geolens::view
