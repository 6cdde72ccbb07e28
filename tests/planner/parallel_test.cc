#include "planner/parallel.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/thread_limit.h"

namespace snooker::planner {
namespace {

// Each task once, on at most min(threads, tasks) workers numbered from 0, the
// caller's thread among them.
TEST(ParallelForTest, RunsEveryTaskOnceOnAtMostTheWorkersAsked) {
  for (const int threads : {-1, 0, 1, 2, 4}) {
    for (const int tasks : {0, 1, 3, 50}) {
      std::vector<std::atomic<int>> runs(static_cast<size_t>(tasks));
      std::mutex mu;
      std::set<int> workers;
      bool caller_ran = tasks == 0;
      const std::thread::id caller = std::this_thread::get_id();
      ParallelFor(threads, tasks, [&](int task, int worker) {
        ++runs[static_cast<size_t>(task)];
        std::lock_guard<std::mutex> lock(mu);
        workers.insert(worker);
        if (std::this_thread::get_id() == caller) {
          caller_ran = true;
          EXPECT_EQ(worker, 0);
        }
      });
      for (int t = 0; t < tasks; ++t) EXPECT_EQ(runs[static_cast<size_t>(t)], 1) << t;
      EXPECT_TRUE(caller_ran);
      const int most = std::max(1, std::min(threads, tasks));
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
    ParallelFor(2, 10000, [&](int task, int) {
      ++ran;
      if (task == 5) throw std::runtime_error("task 5");
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "task 5");
  }
  EXPECT_LT(ran.load(), 10000);
}

// Where the system starts no thread, or one where three were asked, the tasks are
// all done on the workers that did start. Before, a worker that could not start
// threw out of ParallelFor past the joinable threads already running: an abort.
TEST(ParallelForTest, AWorkerTheSystemCannotStartIsDoneWithout) {
  for (const int spare : {0, 1}) {
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
    EXPECT_EQ(run.signal, 0) << "spare " << spare;
    EXPECT_EQ(run.exit_code, 0) << "spare " << spare;
    EXPECT_EQ(run.output, "200 " + std::to_string(spare + 1)) << "spare " << spare;
  }
}

}  // namespace
}  // namespace snooker::planner
