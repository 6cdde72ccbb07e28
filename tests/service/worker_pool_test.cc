#include "server/worker_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "tests/support/thread_limit.h"

namespace snooker::server {
namespace {

// Free workers take a job each at once, at most `max_queued` more wait, and a job
// beyond both is refused; Stop runs what was queued, then refuses.
TEST(WorkerPoolTest, TakesAJobAWorkerPlusTheQueueAndRunsTheQueueOnStop) {
  WorkerPool pool(2, 1);
  EXPECT_EQ(pool.threads(), 2);
  std::mutex mu;
  std::condition_variable cv;
  bool open = false;
  std::atomic<int> started{0}, done{0};
  auto blocked = [&] {
    ++started;
    std::unique_lock<std::mutex> lock(mu);
    cv.wait(lock, [&] { return open; });
    ++done;
  };
  ASSERT_TRUE(pool.TrySubmit(blocked));
  ASSERT_TRUE(pool.TrySubmit(blocked));
  for (int i = 0; i < 2000 && started.load() < 2; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_EQ(started.load(), 2);
  EXPECT_TRUE(pool.TrySubmit(blocked));   // waits in the queue
  EXPECT_FALSE(pool.TrySubmit(blocked));  // beyond the workers and the queue
  {
    std::lock_guard<std::mutex> lock(mu);
    open = true;
  }
  cv.notify_all();
  pool.Stop();
  EXPECT_EQ(done.load(), 3);
  EXPECT_FALSE(pool.TrySubmit([] {}));
}

// A job that throws is reported and its worker takes the next job. Before, the
// exception left the worker's thread: std::terminate, the whole server down.
TEST(WorkerPoolTest, AJobThatThrowsIsReportedAndTheWorkerGoesOn) {
  testing::internal::CaptureStderr();
  std::atomic<int> after{0};
  {
    WorkerPool pool(1, 4);
    ASSERT_TRUE(pool.TrySubmit([] { throw std::runtime_error("no memory left to answer"); }));
    ASSERT_TRUE(pool.TrySubmit([] { throw 7; }));
    ASSERT_TRUE(pool.TrySubmit([&] { ++after; }));
    pool.Stop();
  }
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(after.load(), 1);
  EXPECT_EQ(err,
            "snooker: a worker's job failed: no memory left to answer\n"
            "snooker: a worker's job failed\n");
}

// Where the system can start only one more thread, a pool of four says so, naming
// how far it got. Before, the second thread's failure left the first joinable as the
// pool's members were destroyed: std::terminate, an abort of the whole server.
TEST(WorkerPoolTest, APoolTheSystemCannotStartThrowsAndNamesTheThread) {
  const test_support::LimitedRun run = test_support::RunWithSpareThreads(1, [](std::string* out) {
    try {
      WorkerPool pool(4, 0);
      *out = "started " + std::to_string(pool.threads());
      return 1;
    } catch (const std::runtime_error& e) {
      *out = e.what();
      return 0;
    }
  });
  if (!run.limited) GTEST_SKIP() << run.output;
  EXPECT_EQ(run.signal, 0);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output.rfind("could not start worker thread 2 of 4 (", 0), 0u) << run.output;
}

// A pool that takes as many threads as the system starts: of four asked, with one to
// spare it runs every job on that one; with none it runs each at once on the
// submitter's thread. (The HTTP server's connections are served so.)
std::string AsManyAsPossible() {
  WorkerPool pool(4, 1000, WorkerPool::Start::kAsManyAsPossible);
  std::atomic<int> done{0}, on_caller{0};
  const std::thread::id caller = std::this_thread::get_id();
  int accepted = 0;
  for (int i = 0; i < 20; ++i) {
    accepted += pool.TrySubmit([&] {
      on_caller += std::this_thread::get_id() == caller;
      ++done;
    });
  }
  pool.Stop();
  return std::to_string(pool.threads()) + " threads, " + std::to_string(accepted) + " accepted, " +
         std::to_string(done.load()) + " done, " + std::to_string(on_caller.load()) + " on the caller";
}

void ExpectAsManyAsPossible(int spare, const std::string& expected) {
  const test_support::LimitedRun run = test_support::RunWithSpareThreads(spare, [](std::string* out) {
    *out = AsManyAsPossible();
    return 0;
  });
  if (!run.limited) GTEST_SKIP() << run.output;
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output, expected);
}

TEST(WorkerPoolTest, TakingAsManyAsPossibleWorksOnTheOneThreadToSpare) {
  ExpectAsManyAsPossible(1, "1 threads, 20 accepted, 20 done, 0 on the caller");
}

TEST(WorkerPoolTest, TakingAsManyAsPossibleWithNoThreadRunsJobsOnTheCaller) {
  ExpectAsManyAsPossible(0, "0 threads, 20 accepted, 20 done, 20 on the caller");
}

TEST(WorkerPoolTest, TakingAsManyAsPossibleWithoutALimitTakesAll) {
  EXPECT_EQ(AsManyAsPossible(), "4 threads, 20 accepted, 20 done, 0 on the caller");
}

}  // namespace
}  // namespace snooker::server
