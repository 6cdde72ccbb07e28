// Work shared among a plan's threads. A plan's answer must not depend on which
// thread ran what, so the tasks here are independent: each writes only its own
// result slot and draws from its own random stream.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace snooker::planner {

/// Runs fn(task, worker) for every task in [0, tasks) on at most min(threads, tasks)
/// workers: the caller's thread is worker 0, the others are started here and joined
/// before it returns. Tasks are handed out in order. The first exception a task
/// throws stops the handing out and is rethrown here, after every worker has ended.
/// A worker the system cannot start (no thread to spare: a process or container
/// limit) is done without: the workers already running, the caller's at least,
/// take its tasks, so the answer is the same and only slower.
template <typename Fn>
void ParallelFor(int threads, int tasks, Fn&& fn) {
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&](int worker) {
    try {
      for (int t = next.fetch_add(1); t < tasks; t = next.fetch_add(1)) fn(t, worker);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next.store(tasks);
    }
  };
  std::vector<std::thread> pool;
  const int extra = std::max(0, std::min(threads, tasks) - 1);
  pool.reserve(static_cast<size_t>(extra));
  for (int w = 1; w <= extra; ++w) {
    try {
      pool.emplace_back(work, w);
    } catch (...) {  // std::system_error (no thread) or std::bad_alloc: start no more
      break;
    }
  }
  work(0);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace snooker::planner
