#include "geolens/lens/lens_worker.h"

#include <exception>
#include <utility>

#include "geolens/core/errors.h"

namespace geolens {

LensWorker::LensWorker(LensSession session, std::function<void(const SolveProgress&)> progress)
    : session_(std::move(session)), progress_(std::move(progress)), thread_([this] { run(); }) {}

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
  }
  wake_.notify_all();
  return request;
}

void LensWorker::cancel() {
  std::lock_guard<std::mutex> lock(mutex_);
  waiting_request_ = 0;
  if (busy_) cancel_ = true;
  idle_.notify_all();
}

LensFrame LensWorker::latest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_;
}

void LensWorker::wait_idle() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return !busy_ && waiting_request_ == 0; });
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
    SolveControl control{&cancel_, progress_};
    std::shared_ptr<const LensResult> result;
    std::string error;
    try {
      result = std::make_shared<const LensResult>(session_.update(lenses, control));
    } catch (const Cancelled&) {
      // dropped: latest() keeps the frame before
    } catch (const std::exception& e) {
      error = e.what();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (result) {
        latest_.request = request;
        latest_.result = std::move(result);
        latest_.failed_request = 0;
        latest_.error.clear();
      } else if (!error.empty()) {
        latest_.failed_request = request;
        latest_.error = std::move(error);
      }
      busy_ = false;
    }
    idle_.notify_all();
  }
}

}  // namespace geolens
