#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace geolens {

void parallel_for(size_t n, const std::function<void(size_t, size_t)>& fn, size_t min_chunk) {
  const size_t threads =
      std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), n / min_chunk);
  if (threads < 2) {
    fn(0, n);
    return;
  }
  std::vector<std::thread> workers;
  std::vector<std::exception_ptr> errors(threads);
  const size_t chunk = (n + threads - 1) / threads;
  for (size_t t = 1; t < threads; ++t) {
    workers.emplace_back([&, t] {
      try {
        fn(t * chunk, std::min(n, (t + 1) * chunk));
      } catch (...) {
        errors[t] = std::current_exception();
      }
    });
  }
  try {
    fn(0, std::min(n, chunk));
  } catch (...) {
    errors[0] = std::current_exception();
  }
  for (std::thread& w : workers) w.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

void parallel_for_each(size_t count, const std::function<void(size_t)>& work, int threads) {
  const size_t n_threads = std::min<size_t>(
      threads > 0 ? size_t(threads) : std::max(1u, std::thread::hardware_concurrency()), count);
  if (n_threads <= 1) {
    for (size_t i = 0; i < count; ++i) work(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::vector<std::exception_ptr> errors(n_threads);
  auto worker = [&](size_t t) {
    try {
      for (size_t i = next++; i < count; i = next++) work(i);
    } catch (...) {
      errors[t] = std::current_exception();
      next = count;  // the others stop at their next index
    }
  };
  {
    std::vector<std::jthread> pool;  // joined on destruction, also when a later spawn throws
    pool.reserve(n_threads - 1);
    for (size_t t = 1; t < n_threads; ++t) pool.emplace_back(worker, t);
    worker(0);
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

void parallel_invoke(const std::function<void()>& a, const std::function<void()>& b) {
  std::exception_ptr error;
  std::thread second([&] {
    try {
      b();
    } catch (...) {
      error = std::current_exception();
    }
  });
  try {
    a();
  } catch (...) {
    second.join();
    throw;
  }
  second.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace geolens
