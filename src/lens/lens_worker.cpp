#include "geolens/lens/lens_worker.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
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

  void run();
  // Runs `job` on `lenses` for `request` and makes its answer (or its error) the latest;
  // returns whether the answer is a draft.
  bool publish(std::uint64_t request, const LensJob& job, const std::vector<Lens>& lenses);

  const LensJob job_;
  const LensJob draft_;  // a session's drafts (empty for another job)
  const std::chrono::milliseconds settle_;
  const std::function<void(const SolveProgress&)> progress_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::vector<Lens> waiting_;
  std::uint64_t submitted_ = 0, waiting_request_ = 0;  // waiting_request_ 0: none waits
  bool busy_ = false, stop_ = false;
  bool refining_ = false;  // solving in full a request already shown as a draft
  std::atomic<bool> cancel_{false};
  LensFrame latest_;
  std::thread thread_;  // started once every member above exists
};

LensWorker::LensWorker(LensSession session, std::function<void(const SolveProgress&)> progress,
                       std::chrono::milliseconds settle) {
  auto shared = std::make_shared<LensSession>(std::move(session));
  impl_ = std::make_unique<Impl>(session_job(shared, false), session_job(shared, true),
                                 std::move(progress), settle);
  impl_->thread_ = std::thread([impl = impl_.get()] { impl->run(); });
}

LensWorker::LensWorker(LensJob job, std::function<void(const SolveProgress&)> progress) {
  require(bool(job), "LensWorker", "the job is empty");
  impl_ = std::make_unique<Impl>(std::move(job), nullptr, std::move(progress), kSettle);
  impl_->thread_ = std::thread([impl = impl_.get()] { impl->run(); });
}

LensWorker::~LensWorker() {
  Impl& w = *impl_;
  {
    std::lock_guard<std::mutex> lock(w.mutex_);
    w.stop_ = true;
    w.cancel_ = true;
  }
  w.wake_.notify_all();
  w.thread_.join();
}

std::uint64_t LensWorker::submit(std::vector<Lens> lenses) {
  Impl& w = *impl_;
  std::uint64_t request;
  {
    std::lock_guard<std::mutex> lock(w.mutex_);
    w.waiting_ = std::move(lenses);
    request = w.waiting_request_ = ++w.submitted_;
    if (w.refining_) w.cancel_ = true;  // a full frame of an older request: not worth finishing
  }
  w.wake_.notify_all();
  return request;
}

void LensWorker::cancel() {
  Impl& w = *impl_;
  std::lock_guard<std::mutex> lock(w.mutex_);
  w.waiting_request_ = 0;
  if (w.busy_) w.cancel_ = true;
  w.idle_.notify_all();
  w.wake_.notify_all();  // a draft waiting to settle
}

LensFrame LensWorker::latest() const {
  std::lock_guard<std::mutex> lock(impl_->mutex_);
  return impl_->latest_;
}

bool LensWorker::wait_for(std::uint64_t request, std::chrono::milliseconds timeout) {
  Impl& w = *impl_;
  std::unique_lock<std::mutex> lock(w.mutex_);
  auto answered = [&] {
    return w.latest_.request >= request || w.latest_.failed_request >= request;
  };
  w.idle_.wait_for(lock, timeout,
                   [&] { return answered() || (!w.busy_ && w.waiting_request_ == 0); });
  return answered();
}

void LensWorker::wait_idle() {
  Impl& w = *impl_;
  std::unique_lock<std::mutex> lock(w.mutex_);
  w.idle_.wait(lock, [&w] { return !w.busy_ && w.waiting_request_ == 0; });
}

bool LensWorker::Impl::publish(std::uint64_t request, const LensJob& job,
                               const std::vector<Lens>& lenses) {
  SolveControl control{&cancel_, progress_};
  const auto start = std::chrono::steady_clock::now();
  std::shared_ptr<const Magnification> result;
  std::string error;
  try {
    result = job(lenses, control);
    // A job that cannot stop midway finishes; a cancelled request's answer is dropped all the
    // same.
    if (cancel_.load()) result = nullptr;
  } catch (const Cancelled&) {
    // dropped: latest() keeps the frame before
  } catch (const std::exception& e) {
    error = e.what();
  }
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const bool draft = result && result->draft;
  std::lock_guard<std::mutex> lock(mutex_);
  if (result) {
    latest_.request = request;
    latest_.result = std::move(result);
    latest_.solve_ms = ms;
    latest_.failed_request = 0;
    latest_.error.clear();
  } else if (!error.empty()) {
    latest_.failed_request = request;
    latest_.error = std::move(error);
  }
  idle_.notify_all();  // wait_for
  return draft;
}

void LensWorker::Impl::run() {
  for (;;) {
    std::vector<Lens> lenses;
    std::uint64_t request;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || waiting_request_ != 0; });
      if (stop_) return;
      lenses = std::move(waiting_);
      request = waiting_request_;
      waiting_request_ = 0;
      busy_ = true;
      cancel_ = false;
    }
    // A draft first where there is one; then, unless another request comes within settle_, the
    // same lenses in full.
    bool refine = bool(draft_);
    const LensJob* job = refine ? &draft_ : &job_;
    const auto interrupted = [this] { return stop_ || cancel_ || waiting_request_ != 0; };
    for (;;) {
      const bool draft = publish(request, *job, lenses);
      std::unique_lock<std::mutex> lock(mutex_);
      if (refine && draft) wake_.wait_for(lock, settle_, interrupted);
      if (!refine || !draft || interrupted()) {
        busy_ = refining_ = false;
        break;
      }
      refine = false;
      refining_ = true;
      cancel_ = false;
      job = &job_;
    }
    idle_.notify_all();
  }
}

}  // namespace geolens
