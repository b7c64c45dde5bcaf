#include "lens_solver.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include "geolens/core/errors.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/lens/lens_session.h"
#include "geolens/render/render.h"
#include "geolens/source/mip_pyramid.h"

namespace geolens::view {

std::vector<std::string> method_names() {
  std::vector<std::string> names{"geometric"};
  for (ClassicLens kind : kClassicLenses) names.push_back(to_string(kind));
  return names;
}

bool is_method_name(const std::string& name) {
  for (const std::string& n : method_names())
    if (n == name) return true;
  return false;
}

std::string method_list() {
  std::string list;
  for (const std::string& n : method_names()) list += (list.empty() ? "" : ", ") + n;
  return list;
}

LensSolver::LensSolver(int width, int height, const std::string& method, const LensOptions& options)
    : width_(width), height_(height), method_(method), options_(options) {
  validate(options_);
  if (method_ == "geometric") {
    worker_ = std::make_unique<LensWorker>(LensSession(width_, height_, options_));
  } else {
    ClassicOptions classic;
    classic.mesh = options_.mesh;
    worker_ = std::make_unique<LensWorker>(
        method_job(std::make_shared<const ClassicMethod>(parse_classic_lens(method_), classic),
                   width_, height_));
  }
}

std::uint64_t LensSolver::submit(const std::vector<Lens>& lenses, bool drop_stale) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::uint64_t request = ++submitted_;
  if (drop_stale || lenses.empty()) {
    worker_->cancel();
    pending_.clear();
    shown_worker_request_ = 0;
  }
  if (lenses.empty()) {
    // No method takes an empty list: the identity, at once. The worker's answers to earlier
    // requests are never shown after it.
    auto identity = std::make_shared<Magnification>();
    identity->warp = identity_warp(width_, height_);
    shown_ = SolvedFrame();
    shown_.request = request;
    shown_.result = std::move(identity);
    return request;
  }
  const std::uint64_t worker_request = worker_->submit(lenses);
  pending_[worker_request] = Pending{request, lenses};
  return request;
}

SolvedFrame LensSolver::latest() const {
  LensFrame f = worker_->latest();
  const std::uint64_t request = f.request;
  std::shared_ptr<const Magnification> result = std::move(f.result);
  const double ms = f.solve_ms;
  std::string error = std::move(f.error);
  std::lock_guard<std::mutex> lock(mutex_);
  const auto show = [&] {
    shown_.result = std::move(result);
    shown_.solve_ms = ms;
    shown_.stages.reset();
    shown_.solves = 0;
    if (method_ == "geometric") {
      // A LensSession's worker answers with LensResults (lens_worker.h).
      const auto& solved = static_cast<const LensResult&>(*shown_.result);
      shown_.stages = solved.timings;
      shown_.solves = solved.solves;
    }
  };
  // An answer to a request still pending (not dropped, not older than one already shown); or the
  // full frame of the request shown last as a draft (the worker refines it under its number).
  if (const auto it = pending_.find(request); it != pending_.end()) {
    shown_.request = it->second.request;
    shown_.lenses = it->second.lenses;
    show();
    shown_worker_request_ = request;
    pending_.erase(pending_.begin(), std::next(it));
  } else if (request != 0 && request == shown_worker_request_ && result &&
             result != shown_.result) {
    show();
  }
  shown_.error = std::move(error);
  return shown_;
}

void LensSolver::wait_idle() { worker_->wait_idle(); }

DetailWorker::DetailWorker(std::shared_ptr<const SourceFile> file) : file_(std::move(file)) {
  thread_ = std::thread([this] { run(); });
}

DetailWorker::~DetailWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void DetailWorker::submit(std::shared_ptr<const Magnification> warp, const DetailView& view) {
  std::lock_guard<std::mutex> lock(mutex_);
  waiting_ = std::move(warp);
  waiting_view_ = view;
  wake_.notify_all();
}

std::shared_ptr<const DetailPicture> DetailWorker::latest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_;
}

std::string DetailWorker::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

void DetailWorker::wait_idle() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return !busy_ && !waiting_; });
}

void DetailWorker::run() {
  for (;;) {
    std::shared_ptr<const Magnification> warp;
    DetailView view;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || waiting_; });
      if (stop_) return;
      warp = std::move(waiting_);
      waiting_.reset();
      view = waiting_view_;
      busy_ = true;
    }
    // The warp's screen in the picture's texels: window pixel origin + s * scale, from the
    // covered area's corner, kMaxSide texels a side at most.
    const double fit =
        std::min(1.0, double(DetailPicture::kMaxSide) / double(std::max(view.width, view.height)));
    RenderOptions options;
    options.width = std::max(1, int(std::lround(view.width * fit)));
    options.height = std::max(1, int(std::lround(view.height * fit)));
    WarpMesh framed = warp->warp;
    const Eigen::RowVector2d corner(view.origin.x() - view.x, view.origin.y() - view.y);
    framed.screen = ((framed.screen * view.scale).rowwise() + corner) * fit;
    framed.screen_width = options.width;
    framed.screen_height = options.height;
    auto picture = std::make_shared<DetailPicture>();
    picture->view = view;
    std::string error;
    const auto start = std::chrono::steady_clock::now();
    try {
      picture->image = render(framed, *file_, options);
    } catch (const std::exception& e) {
      error = e.what();
    }
    picture->render_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (error.empty()) latest_ = std::move(picture);
      error_ = std::move(error);
      busy_ = false;
    }
    idle_.notify_all();
  }
}

OpenedSource open_frame(const std::string& path, const SourceFileOptions& options) {
  SourceFile file = open_source(path, options);
  OpenedSource opened;
  opened.path = path;
  opened.kind = file.kind;
  if (const auto* image = dynamic_cast<const MipPyramid*>(file.source.get())) {
    opened.image = image->level(0);  // the pixels as they are, not resampled by the renderer
    return opened;
  }
  RenderOptions render_options;
  render_options.width = file.frame_width;
  render_options.height = file.frame_height;
  opened.image = render(identity_warp(file.frame_width, file.frame_height), file, render_options);
  if (file.scale > 1) opened.detail = std::make_shared<const SourceFile>(std::move(file));
  return opened;
}

SourceOpener::SourceOpener() {
  thread_ = std::thread([this] { run(); });
}

SourceOpener::~SourceOpener() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::uint64_t SourceOpener::submit(const std::string& path, const SourceFileOptions& options) {
  std::lock_guard<std::mutex> lock(mutex_);
  waiting_ = ++submitted_;
  waiting_path_ = path;
  waiting_options_ = options;
  wake_.notify_all();
  return waiting_;
}

std::optional<SourceOpener::Answer> SourceOpener::take() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::optional<Answer> answer = std::move(done_);
  done_.reset();
  return answer;
}

void SourceOpener::wait_idle() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return !busy_ && waiting_ == 0; });
}

void SourceOpener::run() {
  for (;;) {
    Answer answer;
    std::string path;
    SourceFileOptions options;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || waiting_ != 0; });
      if (stop_) return;
      answer.request = waiting_;
      waiting_ = 0;
      path = std::move(waiting_path_);
      options = waiting_options_;
      busy_ = true;
    }
    const auto start = std::chrono::steady_clock::now();
    try {
      answer.opened = open_frame(path, options);
    } catch (const std::exception& e) {
      answer.error = e.what();
    }
    answer.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = std::move(answer);
      busy_ = false;
    }
    idle_.notify_all();
  }
}

}  // namespace geolens::view
