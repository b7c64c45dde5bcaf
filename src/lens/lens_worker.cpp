#include "geolens/lens/lens_worker.h"

#include <chrono>
#include <exception>
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

LensWorker::LensWorker(LensSession session, std::function<void(const SolveProgress&)> progress,
                       std::chrono::milliseconds settle)
    : settle_(settle), progress_(std::move(progress)) {
  auto shared = std::make_shared<LensSession>(std::move(session));
  job_ = session_job(shared, false);
  draft_ = session_job(shared, true);
  thread_ = std::thread([this] { run(); });
}

LensWorker::LensWorker(LensJob job, std::function<void(const SolveProgress&)> progress)
    : job_(std::move(job)), progress_(std::move(progress)) {
  require(bool(job_), "LensWorker", "the job is empty");
  thread_ = std::thread([this] { run(); });
}

LensWorker::~LensWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    cancel_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::uint64_t LensWorker::submit(std::vector<Lens> lenses) {
  std::uint64_t request;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    waiting_ = std::move(lenses);
    request = waiting_request_ = ++submitted_;
    if (refining_) cancel_ = true;  // a full frame of an older request: not worth finishing
  }
  wake_.notify_all();
  return request;
}

void LensWorker::cancel() {
  std::lock_guard<std::mutex> lock(mutex_);
  waiting_request_ = 0;
  if (busy_) cancel_ = true;
  idle_.notify_all();
  wake_.notify_all();  // a draft waiting to settle
}

LensFrame LensWorker::latest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_;
}

bool LensWorker::wait_for(std::uint64_t request, std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  auto answered = [&] { return latest_.request >= request || latest_.failed_request >= request; };
  idle_.wait_for(lock, timeout, [&] { return answered() || (!busy_ && waiting_request_ == 0); });
  return answered();
}

void LensWorker::wait_idle() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return !busy_ && waiting_request_ == 0; });
}

bool LensWorker::publish(std::uint64_t request, const LensJob& job,
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

void LensWorker::run() {
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
