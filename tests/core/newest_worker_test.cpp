// NewestWorker (core/solve_control.h): jobs run one at a time on the worker's thread, a waiting
// job is replaced by a newer one, cancel and cancel_on_newer reach the job under way, quiet_for
// wakes on a newer job, wait_for and wait_idle return when they say.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/core/solve_control.h"

namespace geolens {
namespace {

using namespace std::chrono_literals;

// A job that says it started, then waits until released (or cancelled, if it listens).
struct Gate {
  std::promise<void> started, release;
  std::shared_future<void> released{release.get_future().share()};
};

TEST(NewestWorkerTest, AJobWaitingIsReplacedByANewerOne) {
  NewestWorker worker;
  Gate gate;
  std::mutex mutex;
  std::vector<std::pair<int, std::uint64_t>> ran;  // the job's own number, its request's
  const auto job = [&](int number) {
    return [&, number](NewestWorker::Run& run) {
      std::lock_guard<std::mutex> lock(mutex);
      ran.emplace_back(number, run.request());
    };
  };
  EXPECT_EQ(worker.submit([&](NewestWorker::Run& run) {
    gate.started.set_value();
    gate.released.wait();
    job(1)(run);
  }),
            1u);
  gate.started.get_future().wait();
  EXPECT_EQ(worker.submit(job(2)), 2u);
  EXPECT_EQ(worker.submit(job(3)), 3u);
  EXPECT_EQ(worker.submit(job(4)), 4u);
  gate.release.set_value();
  worker.wait_idle();
  EXPECT_EQ(ran, (std::vector<std::pair<int, std::uint64_t>>{{1, 1}, {4, 4}}));
}

TEST(NewestWorkerTest, CancelStopsTheJobUnderWayAndDropsTheWaitingOne) {
  NewestWorker worker;
  std::promise<void> started;
  std::atomic<bool> saw_cancel{false}, waiting_ran{false};
  worker.submit([&](NewestWorker::Run& run) {
    started.set_value();
    while (!run.cancelled()) std::this_thread::sleep_for(1ms);
    saw_cancel = true;
  });
  started.get_future().wait();
  worker.submit([&](NewestWorker::Run&) { waiting_ran = true; });
  worker.cancel();
  worker.wait_idle();
  EXPECT_TRUE(saw_cancel);
  EXPECT_FALSE(waiting_ran);
}

TEST(NewestWorkerTest, ANewerJobCancelsOnlyAfterCancelOnNewer) {
  NewestWorker worker;
  std::atomic<bool> cancelled_before{true}, cancelled_after{false};
  Gate gate;
  worker.submit([&](NewestWorker::Run& run) {
    gate.started.set_value();
    gate.released.wait();  // a newer job has been submitted meanwhile
    cancelled_before = run.cancelled().load();
    run.cancel_on_newer();  // one waits already: cancelled at once
    cancelled_after = run.cancelled().load();
  });
  gate.started.get_future().wait();
  worker.submit([](NewestWorker::Run&) {});
  gate.release.set_value();
  worker.wait_idle();
  EXPECT_FALSE(cancelled_before);
  EXPECT_TRUE(cancelled_after);
}

TEST(NewestWorkerTest, AfterCancelOnNewerANewerJobCancels) {
  NewestWorker worker;
  std::promise<void> listening;
  std::atomic<bool> cancelled{false};
  worker.submit([&](NewestWorker::Run& run) {
    run.cancel_on_newer();
    listening.set_value();
    const auto start = std::chrono::steady_clock::now();
    while (!run.cancelled() && std::chrono::steady_clock::now() - start < 10s)
      std::this_thread::sleep_for(1ms);
    cancelled = run.cancelled().load();
  });
  listening.get_future().wait();
  worker.submit([](NewestWorker::Run&) {});
  worker.wait_idle();
  EXPECT_TRUE(cancelled);
}

TEST(NewestWorkerTest, QuietForWakesOnANewerJob) {
  NewestWorker worker;
  std::atomic<bool> quiet_alone{false}, quiet_with_newer{true};
  std::promise<void> waiting;
  std::atomic<double> waited_ms{0};
  worker.submit([&](NewestWorker::Run& run) { quiet_alone = run.quiet_for(5ms); });
  worker.wait_idle();
  EXPECT_TRUE(quiet_alone);
  worker.submit([&](NewestWorker::Run& run) {
    waiting.set_value();
    const auto start = std::chrono::steady_clock::now();
    quiet_with_newer = run.quiet_for(10s);
    waited_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  });
  waiting.get_future().wait();
  worker.submit([](NewestWorker::Run&) {});
  worker.wait_idle();
  EXPECT_FALSE(quiet_with_newer);
  EXPECT_LT(waited_ms.load(), 5000.0);
}

TEST(NewestWorkerTest, WaitForTellsAnsweredFromIdle) {
  NewestWorker worker;
  const std::uint64_t answered = worker.submit([](NewestWorker::Run& run) { run.answered(); });
  EXPECT_TRUE(worker.wait_for(answered, 10s));
  // A job that returns without answering: wait_for gives up when the worker is idle, not after
  // its timeout.
  const std::uint64_t silent = worker.submit([](NewestWorker::Run&) {});
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(worker.wait_for(silent, 10s));
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5s);
  // An answer of a later request answers an earlier one.
  EXPECT_TRUE(worker.wait_for(answered, 0ms));
}

TEST(NewestWorkerTest, DestroyingCancelsTheJobUnderWay) {
  std::atomic<bool> saw_cancel{false};
  {
    NewestWorker worker;
    std::promise<void> started;
    worker.submit([&](NewestWorker::Run& run) {
      started.set_value();
      while (!run.cancelled()) std::this_thread::sleep_for(1ms);
      saw_cancel = true;
    });
    started.get_future().wait();
  }
  EXPECT_TRUE(saw_cancel);
}

TEST(NewestWorkerTest, AnEmptyJobIsRefused) {
  NewestWorker worker;
  EXPECT_THROW(worker.submit(nullptr), InvalidInput);
}

}  // namespace
}  // namespace geolens
