#include "geolens/lens/lens_worker.h"

#include <chrono>
#include <exception>
#include <mutex>
#include <utility>

#include "geolens/core/errors.h"

namespace geolens {

LensJob method_job(std::shared_ptr<const LensMethod> method, double width, double height) {
  require(method != nullptr, "method_job", "the method is null");
  return [method = std::move(method), width, height](const std::vector<Lens>& lenses,
                                                     const SolveControl&) {
    return std::shared_ptr<const Magnification>(
        std::make_shared<const Magnification>(method->magnify(lenses, width, height)));
  };
}

namespace {

// A session's update as a job: full frames, or drafts.
LensJob session_job(std::shared_ptr<LensSession> session, bool draft) {
  return [session = std::move(session), draft](const std::vector<Lens>& lenses,
                                               const SolveControl& control) {
    return std::shared_ptr<const Magnification>(
        std::make_shared<const LensResult>(session->update(lenses, control, draft)));
  };
}

}  // namespace

struct LensWorker::Impl {
  Impl(LensJob job, LensJob draft, std::function<void(const SolveProgress&)> progress,
       std::chrono::milliseconds settle)
      : job_(std::move(job)),
        draft_(std::move(draft)),
        settle_(settle),
        progress_(std::move(progress)) {}

  // A request's work: a draft first where there is one; then, unless another request comes
  // within settle_, the same lenses in full (stopped by a newer request).
  void solve(NewestWorker::Run& run, const std::vector<Lens>& lenses);
  // Runs `job` on `lenses` and makes its answer (or its error) the latest; returns whether the
  // answer is a draft.
  bool publish(NewestWorker::Run& run, const LensJob& job, const std::vector<Lens>& lenses);

  const LensJob job_;
  const LensJob draft_;  // a session's drafts (empty for another job)
  const std::chrono::milliseconds settle_;
  const std::function<void(const SolveProgress&)> progress_;
  mutable std::mutex mutex_;
  LensFrame latest_;
  NewestWorker worker_;  // last: destroyed (its thread joined) before the members above
};

LensWorker::LensWorker(LensSession session, std::function<void(const SolveProgress&)> progress,
                       std::chrono::milliseconds settle) {
  auto shared = std::make_shared<LensSession>(std::move(session));
  impl_ = std::make_unique<Impl>(session_job(shared, false), session_job(shared, true),
                                 std::move(progress), settle);
}

LensWorker::LensWorker(LensJob job, std::function<void(const SolveProgress&)> progress) {
  require(bool(job), "LensWorker", "the job is empty");
  impl_ = std::make_unique<Impl>(std::move(job), nullptr, std::move(progress), kSettle);
}

LensWorker::~LensWorker() = default;

std::uint64_t LensWorker::submit(std::vector<Lens> lenses) {
  return impl_->worker_.submit([impl = impl_.get(), lenses = std::move(lenses)](
                                   NewestWorker::Run& run) { impl->solve(run, lenses); });
}

void LensWorker::cancel() { impl_->worker_.cancel(); }

LensFrame LensWorker::latest() const {
  std::lock_guard<std::mutex> lock(impl_->mutex_);
  return impl_->latest_;
}

bool LensWorker::wait_for(std::uint64_t request, std::chrono::milliseconds timeout) {
  return impl_->worker_.wait_for(request, timeout);
}

void LensWorker::wait_idle() { impl_->worker_.wait_idle(); }

void LensWorker::Impl::solve(NewestWorker::Run& run, const std::vector<Lens>& lenses) {
  if (draft_) {
    if (!publish(run, draft_, lenses) || !run.quiet_for(settle_)) return;
    run.cancel_on_newer();  // a full frame of an older request: not worth finishing
  }
  publish(run, job_, lenses);
}

bool LensWorker::Impl::publish(NewestWorker::Run& run, const LensJob& job,
                               const std::vector<Lens>& lenses) {
  SolveControl control{&run.cancelled(), progress_};
  const auto start = std::chrono::steady_clock::now();
  std::shared_ptr<const Magnification> result;
  std::string error;
  try {
    result = job(lenses, control);
    // A job that cannot stop midway finishes; a cancelled request's answer is dropped all the
    // same.
    if (run.cancelled().load()) result = nullptr;
  } catch (const Cancelled&) {
    // dropped: latest() keeps the frame before
  } catch (const std::exception& e) {
    error = e.what();
  }
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const bool draft = result && result->draft, answered = result || !error.empty();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (result) {
      latest_.request = run.request();
      latest_.result = std::move(result);
      latest_.solve_ms = ms;
      latest_.failed_request = 0;
      latest_.error.clear();
    } else if (!error.empty()) {
      latest_.failed_request = run.request();
      latest_.error = std::move(error);
    }
  }
  if (answered) run.answered();
  return draft;
}

}  // namespace geolens
