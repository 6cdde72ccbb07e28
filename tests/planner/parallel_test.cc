#include "planner/parallel.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/thread_limit.h"

namespace snooker::planner {
namespace {

// Each task once, on at most min(threads, tasks) workers numbered from 0; the
// caller's thread is worker 0, and the only one where one worker is all there is.
TEST(ParallelForTest, RunsEveryTaskOnceOnAtMostTheWorkersAsked) {
  for (const int threads : {-1, 0, 1, 2, 4}) {
    for (const int tasks : {0, 1, 3, 50}) {
      std::vector<std::atomic<int>> runs(static_cast<size_t>(tasks));
      std::mutex mu;
      std::set<int> workers;
      bool only_the_caller = true;
      const std::thread::id caller = std::this_thread::get_id();
      ParallelFor(threads, tasks, [&](int task, int worker) {
        ++runs[static_cast<size_t>(task)];
        std::lock_guard<std::mutex> lock(mu);
        workers.insert(worker);
        if (std::this_thread::get_id() == caller) {
          EXPECT_EQ(worker, 0);
        } else {
          only_the_caller = false;
        }
      });
      for (int t = 0; t < tasks; ++t) EXPECT_EQ(runs[static_cast<size_t>(t)], 1) << t;
      const int most = std::max(1, std::min(threads, tasks));
      if (most == 1) {
        EXPECT_TRUE(only_the_caller) << "threads " << threads << ", tasks " << tasks;
      }
      for (const int w : workers) {
        EXPECT_GE(w, 0);
        EXPECT_LT(w, most) << "threads " << threads << ", tasks " << tasks;
      }
    }
  }
}

// The first exception is rethrown to the caller, after the handing out stopped.
TEST(ParallelForTest, ATasksExceptionStopsTheRestAndReachesTheCaller) {
  std::atomic<int> ran{0};
  try {
    ParallelFor(2, 2000, [&](int task, int) {
      ++ran;
      // Slow enough that the other worker cannot finish them all while the throw unwinds.
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      if (task == 5) throw std::runtime_error("task 5");
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "task 5");
  }
  EXPECT_LT(ran.load(), 2000);
}

// ParallelFor asked for four workers and 200 tasks, in a copy of this test where
// the system starts only `spare` more threads: every task done once, on the workers
// that did start. Before, a worker that could not start threw out of ParallelFor
// past the joinable threads already running: with one to spare, an abort.
void ExpectEveryTaskOnceOnTheWorkersThatStart(int spare) {
  const test_support::LimitedRun run = test_support::RunWithSpareThreads(spare, [](std::string* out) {
    constexpr int kTasks = 200;
    std::vector<std::atomic<int>> runs(kTasks);
    std::mutex mu;
    std::set<int> workers;
    ParallelFor(4, kTasks, [&](int task, int worker) {
      ++runs[static_cast<size_t>(task)];
      std::this_thread::sleep_for(std::chrono::microseconds(200));  // so that every worker takes some
      std::lock_guard<std::mutex> lock(mu);
      workers.insert(worker);
    });
    int once = 0;
    for (const std::atomic<int>& r : runs) once += r.load() == 1;
    *out = std::to_string(once) + " " + std::to_string(workers.size());
    return 0;
  });
  if (!run.limited) GTEST_SKIP() << run.output;
  EXPECT_EQ(run.signal, 0);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output, "200 " + std::to_string(spare + 1));
}

TEST(ParallelForTest, WithNoThreadToSpareTheCallerDoesEveryTask) { ExpectEveryTaskOnceOnTheWorkersThatStart(0); }

TEST(ParallelForTest, WithOneThreadToSpareTwoWorkersDoEveryTask) { ExpectEveryTaskOnceOnTheWorkersThatStart(1); }

}  // namespace
}  // namespace snooker::planner
