#include "core/thread_pool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/parallel.h"
#include "geolens/core/errors.h"

namespace geolens {
namespace {

// Runs `count` indices on `pool` and checks that each ran exactly once.
void expect_each_index_once(ThreadPool& pool, size_t count) {
  std::vector<std::atomic<int>> runs(count);
  pool.run(count, [&](size_t i) { ++runs[i]; });
  for (size_t i = 0; i < count; ++i)
    ASSERT_EQ(runs[i].load(), 1) << "index " << i << " of " << count;
}

TEST(ThreadPool, RunsEveryIndexExactlyOnce) {
  for (const int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    EXPECT_EQ(pool.size(), threads);
    // The same pool, loop after loop: the workers are kept.
    for (const size_t count : {0, 1, 2, 3, 7, 100, 10000}) {
      SCOPED_TRACE("threads " + std::to_string(threads) + ", count " + std::to_string(count));
      expect_each_index_once(pool, count);
    }
  }
}

TEST(ThreadPool, ZeroThreadsMeansOnePerHardwareThreadAndOutOfRangeIsRejected) {
  EXPECT_EQ(ThreadPool(0).size(), int(std::max(1u, std::thread::hardware_concurrency())));
  EXPECT_THROW(ThreadPool(-1), InvalidInput);
  // A typo's 100000 is refused by the limit, before the system runs out of threads.
  EXPECT_THROW(ThreadPool(ThreadPool::kMaxThreads + 1), InvalidInput);
  EXPECT_THROW(ThreadPool(100000), InvalidInput);
}

TEST(ThreadPool, OneThreadRunsEverythingOnTheCallingThread) {
  ThreadPool pool(1);
  const std::thread::id caller = std::this_thread::get_id();
  std::vector<std::thread::id> ran(50);
  pool.run(ran.size(), [&](size_t i) { ran[i] = std::this_thread::get_id(); });
  for (const std::thread::id& id : ran) EXPECT_EQ(id, caller);
}

// Two tasks that each wait for the other can only finish if two threads run them at once.
TEST(ThreadPool, TwoThreadsRunTwoTasksAtOnce) {
  ThreadPool pool(2);
  std::mutex mutex;
  std::condition_variable arrived;
  int waiting = 0;
  std::atomic<int> met{0};
  pool.run(2, [&](size_t) {
    std::unique_lock<std::mutex> lock(mutex);
    ++waiting;
    arrived.notify_all();
    if (arrived.wait_for(lock, std::chrono::seconds(10), [&] { return waiting == 2; })) ++met;
  });
  EXPECT_EQ(met.load(), 2);
}

TEST(ThreadPool, TheFirstExceptionPropagatesAndThePoolStaysUsable) {
  for (const int threads : {1, 2, 4}) {
    ThreadPool pool(threads);
    std::atomic<int> started{0};
    EXPECT_THROW(pool.run(1000,
                          [&](size_t i) {
                            ++started;
                            if (i == 5) throw std::runtime_error("index 5");
                            // Long enough that the others cannot finish while it unwinds.
                            std::this_thread::sleep_for(std::chrono::microseconds(100));
                          }),
                 std::runtime_error);
    EXPECT_LT(started.load(), 500);  // the hand-out stopped
    // Every task throws: one of the exceptions comes out, nothing hangs.
    EXPECT_THROW(pool.run(100, [](size_t) { throw InvalidInput("every index"); }), InvalidInput);
    expect_each_index_once(pool, 1000);
  }
}

TEST(ThreadPool, ARunInsideATaskRunsInlineWithoutDeadlock) {
  ThreadPool pool(3);
  std::vector<std::atomic<int>> runs(8 * 50);
  pool.run(8, [&](size_t outer) {
    pool.run(50, [&](size_t inner) { ++runs[outer * 50 + inner]; });
    parallel_for(
        pool, 50,
        [&](size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i) ++runs[outer * 50 + i];
        },
        1);
  });
  for (const std::atomic<int>& r : runs) EXPECT_EQ(r.load(), 2);
}

// Callers on two threads at once: one has the workers, the other runs its loop itself.
TEST(ThreadPool, CallersOnSeveralThreadsShareThePool) {
  ThreadPool pool(2);
  std::vector<std::atomic<int>> a(20000), b(20000);
  std::thread other([&] {
    for (int k = 0; k < 20; ++k) pool.run(a.size(), [&](size_t i) { ++a[i]; });
  });
  for (int k = 0; k < 20; ++k) pool.run(b.size(), [&](size_t i) { ++b[i]; });
  other.join();
  for (size_t i = 0; i < a.size(); ++i) ASSERT_TRUE(a[i] == 20 && b[i] == 20) << i;
}

TEST(ParallelFor, CoversTheRangeOnceInDisjointChunks) {
  for (const int threads : {1, 2, 5}) {
    ThreadPool pool(threads);
    for (const size_t n : {0, 1, 7, 8, 9, 100, 12345}) {
      for (const size_t min_chunk : {1, 4, 4096}) {
        std::vector<std::atomic<int>> runs(n);
        std::atomic<int> calls{0};
        parallel_for(
            pool, n,
            [&](size_t begin, size_t end) {
              EXPECT_LE(begin, end);
              ++calls;
              for (size_t i = begin; i < end; ++i) ++runs[i];
            },
            min_chunk);
        for (size_t i = 0; i < n; ++i) ASSERT_EQ(runs[i].load(), 1) << i;
        // One call below 2 min_chunk or on one thread; at most one chunk per thread.
        if (n < 2 * min_chunk || threads == 1) EXPECT_EQ(calls.load(), 1);
        EXPECT_LE(calls.load(), std::max(threads, 1));
      }
    }
  }
}

TEST(ParallelInvoke, RunsBothAndRethrows) {
  for (const int threads : {1, 2}) {
    ThreadPool pool(threads);
    int a = 0, b = 0;
    parallel_invoke(
        pool, [&] { a = 1; }, [&] { b = 2; });
    EXPECT_EQ(a + b, 3);
    EXPECT_THROW(parallel_invoke(
                     pool, [] {}, [] { throw SolverError("b"); }),
                 SolverError);
    parallel_invoke(
        pool, [&] { a = 3; }, [&] { b = 4; });
    EXPECT_EQ(a + b, 7);
  }
}

}  // namespace
}  // namespace geolens
