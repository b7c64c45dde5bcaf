#include "lens_solver.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include "geolens/core/errors.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/lens/lens_session.h"
#include "geolens/render/render.h"
#include "geolens/source/source.h"

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
    // A drag's drafts on a grid of at most kDraftMesh (drawing the triangles that move is most
    // of a drag's frame under Mesa's llvmpipe: 27 ms at 100 x 100 and 84 ms at 200 x 200, against
    // a 10 ms floor, with drafts on the grid asked), the full frame once the lens rests.
    LensOptions o = options_;
    if (o.draft_mesh == 0) o.draft_mesh = std::min(o.mesh, kDraftMesh);
    worker_ = std::make_unique<LensWorker>(LensSession(width_, height_, o));
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

void LensSolver::wait_for_last(std::chrono::milliseconds timeout) {
  std::uint64_t request;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pending_.empty()) return;  // answered, dropped, or the identity
    request = pending_.rbegin()->first;
  }
  worker_->wait_for(request, timeout);
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
    shown_.fit_reasons.clear();
    if (method_ == "geometric") {
      // A LensSession's worker answers with LensResults (lens_worker.h).
      const auto& solved = static_cast<const LensResult&>(*shown_.result);
      shown_.stages = solved.timings;
      shown_.solves = solved.solves;
      shown_.fit_reasons = solved.zoom_fit_reasons;
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

DetailWorker::DetailWorker(std::shared_ptr<const SourceFile> file)
    : worker_([file = std::move(file),
               last = std::shared_ptr<const DetailPicture>()](const Request& r) mutable {
        // The warp's screen in the picture's texels: window pixel origin + s * scale, from the
        // covered area's corner, kMaxSide texels a side at most.
        const DetailView& view = r.view;
        const double fit = std::min(
            1.0, double(DetailPicture::kMaxSide) / double(std::max(view.width, view.height)));
        RenderOptions options;
        options.width = std::max(1, int(std::lround(view.width * fit)));
        options.height = std::max(1, int(std::lround(view.height * fit)));
        WarpMesh framed = r.warp->warp;
        const Eigen::RowVector2d corner(view.origin.x() - view.x, view.origin.y() - view.y);
        framed.screen = ((framed.screen * view.scale).rowwise() + corner) * fit;
        framed.screen_width = options.width;
        framed.screen_height = options.height;
        auto picture = std::make_shared<DetailPicture>();
        picture->view = view;
        const auto start = std::chrono::steady_clock::now();
        try {
          picture->image = render(framed, *file, options);
        } catch (const std::exception& e) {
          return Answer{last, e.what()};
        }
        picture->render_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        last = std::move(picture);
        return Answer{last, ""};
      }) {}

std::shared_ptr<const DetailPicture> DetailWorker::latest() const {
  const auto done = worker_.latest();
  return done ? done->answer.picture : nullptr;
}

std::string DetailWorker::error() const {
  const auto done = worker_.latest();
  return done ? done->answer.error : std::string();
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

SourceOpener::SourceOpener()
    : worker_([](const Request& r) {
        try {
          return Opened{open_frame(r.path, r.options), ""};
        } catch (const std::exception& e) {
          return Opened{std::nullopt, e.what()};
        }
      }) {}

std::optional<SourceOpener::Answer> SourceOpener::take() {
  const auto done = worker_.latest();
  if (!done || done->request == taken_) return std::nullopt;
  taken_ = done->request;
  return Answer{done->request, done->answer.opened, done->answer.error, done->ms};
}

}  // namespace geolens::view
