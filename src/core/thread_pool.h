#pragma once
// The library's worker threads: one pool, started once, that runs parallel loops (the lens's
// per-triangle steps, the renderer's chunks and bands). Its owner sets its size.

#include <cstddef>
#include <functional>
#include <memory>

namespace geolens {

/// A fixed set of worker threads, started by the constructor and kept until the destructor,
/// that run loops over [0, count) with the calling thread.
///
/// Threading: run() may be called from any thread. One call at a time has the workers; a call
/// made while another runs (from another thread, or from inside one of its tasks) runs its whole
/// loop on its own calling thread instead. So users of one pool never wait for each other and a
/// nested run() cannot deadlock; they only share the cores. Which thread runs an index never
/// changes a result in the library: loops write disjoint ranges and reduce in a fixed order.
///
/// Not copyable or movable; objects that share a pool hold a std::shared_ptr to it.
class ThreadPool {
 public:
  /// The most threads a pool runs (a typo's 100000 would exhaust the system's threads first).
  static constexpr int kMaxThreads = 1024;
  /// @param threads  threads that run a loop, the calling thread included: 0 = one per hardware
  ///                 thread (std::thread::hardware_concurrency, at least 1); 1 = every loop on
  ///                 the calling thread, no worker started. Throws InvalidInput if < 0 or above
  ///                 kMaxThreads, SolverError if the system cannot start them.
  explicit ThreadPool(int threads = 0);
  /// Stops and joins the workers; no run() may be in progress.
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// Threads that run a loop, the calling thread included (>= 1).
  int size() const { return size_; }

  /// Calls task(i) once for every i in [0, count), handing the indices out in increasing order
  /// to the workers and the calling thread as each becomes free (uneven costs balance), and
  /// returns when all are done. If a task throws, no further index is handed out; the first
  /// exception is rethrown once every started task has returned, and the pool stays usable.
  void run(size_t count, const std::function<void(size_t)>& task);

 private:
  struct State;
  int size_;
  std::unique_ptr<State> state_;
};

}  // namespace geolens
