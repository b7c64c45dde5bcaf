#include "core/thread_pool.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "geolens/core/errors.h"

namespace geolens {

namespace {

// One loop of run(): its indices and its first error.
struct Loop {
  const std::function<void(size_t)>* task;
  size_t count;
  std::atomic<size_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  int active = 0;  // workers inside work(); guarded by State::mutex

  // Takes indices until none is left, recording the first exception and stopping the hand-out.
  void work() {
    for (size_t i = next++; i < count; i = next++) {
      try {
        (*task)(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = count;  // the others stop at their next index
      }
    }
  }
};

}  // namespace

struct ThreadPool::State {
  std::mutex mutex;
  std::condition_variable wake;   // a loop was posted, or stop
  std::condition_variable done;   // a worker left the loop
  Loop* loop = nullptr;           // the loop workers may join; guarded by mutex
  uint64_t generation = 0;        // loops posted; guarded by mutex
  bool stop = false;              // guarded by mutex
  std::atomic<bool> busy{false};  // a run() has the workers
  std::vector<std::thread> workers;

  void worker() {
    uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
      wake.wait(lock, [&] { return stop || generation != seen; });
      if (stop) return;
      seen = generation;
      Loop* current = loop;
      if (current == nullptr) continue;  // posted and already finished
      ++current->active;
      lock.unlock();
      current->work();
      lock.lock();
      if (--current->active == 0) done.notify_one();
    }
  }

  void join() {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      stop = true;
    }
    wake.notify_all();
    for (std::thread& w : workers) w.join();
  }
};

ThreadPool::ThreadPool(int threads) : state_(std::make_unique<State>()) {
  require(threads >= 0 && threads <= kMaxThreads, "ThreadPool",
          "threads must be in [0, " + std::to_string(kMaxThreads) + "], got " +
              std::to_string(threads));
  size_ =
      threads > 0 ? threads : std::clamp(int(std::thread::hardware_concurrency()), 1, kMaxThreads);
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
  // WebAssembly without threads (built without -pthread): std::thread cannot start one
  // (pthread_create fails with EAGAIN), so every loop runs on the calling thread, whatever was
  // asked; results do not depend on the number of threads.
  size_ = 1;
#endif
  try {
    state_->workers.reserve(size_t(size_ - 1));
    for (int t = 1; t < size_; ++t)
      state_->workers.emplace_back([s = state_.get()] { s->worker(); });
  } catch (const std::system_error& e) {
    state_->join();  // the workers already started
    throw SolverError("ThreadPool: cannot start " + std::to_string(size_) + " threads (" +
                      e.what() + "); ask for fewer");
  } catch (...) {
    state_->join();
    throw;
  }
}

ThreadPool::~ThreadPool() { state_->join(); }

void ThreadPool::run(size_t count, const std::function<void(size_t)>& task) {
  State& s = *state_;
  bool idle = false;
  if (count < 2 || s.workers.empty() || !s.busy.compare_exchange_strong(idle, true)) {
    // One index, no workers, or the workers are taken (another caller, or a task of this
    // pool's calling run()): the whole loop on this thread.
    for (size_t i = 0; i < count; ++i) task(i);
    return;
  }
  Loop loop;
  loop.task = &task;
  loop.count = count;
  {
    const std::lock_guard<std::mutex> lock(s.mutex);
    s.loop = &loop;
    ++s.generation;
  }
  s.wake.notify_all();
  loop.work();
  {
    // No worker joins from here on; wait for those that did.
    std::unique_lock<std::mutex> lock(s.mutex);
    s.loop = nullptr;
    s.done.wait(lock, [&] { return loop.active == 0; });
  }
  s.busy.store(false, std::memory_order_release);
  if (loop.error) std::rethrow_exception(loop.error);
}

}  // namespace geolens
