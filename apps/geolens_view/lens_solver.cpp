#include "lens_solver.h"

#include <utility>

#include "geolens/core/errors.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/lens/lens_session.h"

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
  // An answer to a request still pending (not dropped, not older than one already shown).
  if (const auto it = pending_.find(request); it != pending_.end()) {
    shown_.request = it->second.request;
    shown_.result = std::move(result);
    shown_.lenses = it->second.lenses;
    shown_.solve_ms = ms;
    shown_.stages.reset();
    shown_.solves = 0;
    if (method_ == "geometric") {
      // A LensSession's worker answers with LensResults (lens_worker.h).
      const auto& solved = static_cast<const LensResult&>(*shown_.result);
      shown_.stages = solved.timings;
      shown_.solves = solved.solves;
    }
    pending_.erase(pending_.begin(), std::next(it));
  }
  shown_.error = std::move(error);
  return shown_;
}

void LensSolver::wait_idle() { worker_->wait_idle(); }

}  // namespace geolens::view
