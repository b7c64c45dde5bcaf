#include "geolens/core/solve_control.h"

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "geolens/core/errors.h"

namespace geolens {

void SolveControl::step(const SolveProgress& p, const char* function) const {
  if (progress) progress(p);
  if (cancel != nullptr && cancel->load(std::memory_order_relaxed))
    throw Cancelled(std::string(function) + ": cancelled");
}

struct NewestWorker::Impl {
  void run();
  // Whether the job under way should stop waiting (Run::quiet_for). Under `mutex`.
  bool interrupted() const { return stop || cancel || waiting_request != 0; }

  std::mutex mutex;
  std::condition_variable wake, idle;
  Job waiting;
  std::uint64_t submitted = 0, waiting_request = 0;  // waiting_request 0: none waits
  std::uint64_t answered = 0;                        // the latest request answered
  bool busy = false, stop = false, cancel_on_newer = false;
  std::atomic<bool> cancel{false};
  std::thread thread;  // started once every member above exists
};

void NewestWorker::Impl::run() {
  for (;;) {
    Run run;
    run.worker_ = this;
    Job job;
    {
      std::unique_lock<std::mutex> lock(mutex);
      wake.wait(lock, [this] { return stop || waiting_request != 0; });
      if (stop) return;
      job = std::move(waiting);
      waiting = nullptr;
      run.request_ = waiting_request;
      waiting_request = 0;
      busy = true;
      cancel = false;
      cancel_on_newer = false;
    }
    job(run);
    {
      std::lock_guard<std::mutex> lock(mutex);
      busy = cancel_on_newer = false;
    }
    idle.notify_all();
  }
}

const std::atomic<bool>& NewestWorker::Run::cancelled() const { return worker_->cancel; }

bool NewestWorker::Run::quiet_for(std::chrono::milliseconds quiet) const {
  std::unique_lock<std::mutex> lock(worker_->mutex);
  return !worker_->wake.wait_for(lock, quiet, [w = worker_] { return w->interrupted(); });
}

void NewestWorker::Run::cancel_on_newer() {
  std::lock_guard<std::mutex> lock(worker_->mutex);
  worker_->cancel_on_newer = true;
  if (worker_->waiting_request != 0) worker_->cancel = true;
}

void NewestWorker::Run::answered() {
  {
    std::lock_guard<std::mutex> lock(worker_->mutex);
    worker_->answered = std::max(worker_->answered, request_);
  }
  worker_->idle.notify_all();
}

NewestWorker::NewestWorker() : impl_(std::make_unique<Impl>()) {
  impl_->thread = std::thread([impl = impl_.get()] { impl->run(); });
}

NewestWorker::~NewestWorker() {
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->stop = true;
    impl_->cancel = true;
  }
  impl_->wake.notify_all();
  impl_->thread.join();
}

std::uint64_t NewestWorker::submit(Job job) {
  require(bool(job), "NewestWorker::submit", "the job is empty");
  Impl& w = *impl_;
  std::uint64_t request;
  {
    std::lock_guard<std::mutex> lock(w.mutex);
    w.waiting = std::move(job);
    request = w.waiting_request = ++w.submitted;
    if (w.busy && w.cancel_on_newer) w.cancel = true;
  }
  w.wake.notify_all();
  return request;
}

void NewestWorker::cancel() {
  Impl& w = *impl_;
  {
    std::lock_guard<std::mutex> lock(w.mutex);
    w.waiting = nullptr;
    w.waiting_request = 0;
    if (w.busy) w.cancel = true;
  }
  w.idle.notify_all();
  w.wake.notify_all();  // a job waiting for quiet
}

void NewestWorker::wait_idle() {
  Impl& w = *impl_;
  std::unique_lock<std::mutex> lock(w.mutex);
  w.idle.wait(lock, [&w] { return !w.busy && w.waiting_request == 0; });
}

bool NewestWorker::wait_for(std::uint64_t request, std::chrono::milliseconds timeout) {
  Impl& w = *impl_;
  std::unique_lock<std::mutex> lock(w.mutex);
  w.idle.wait_for(lock, timeout,
                  [&] { return w.answered >= request || (!w.busy && w.waiting_request == 0); });
  return w.answered >= request;
}

}  // namespace geolens
