// A fixed set of threads that run the service's calls, with a bounded queue. gRPC's
// callback API must not block its own threads, and a fixed pool bounds how many
// calls compute at once (so memory is bounded by threads x the largest call) and
// how many may wait; a call beyond both is refused at once. The HTTP server's
// connections have a pool of their own (as many threads as the system starts, a
// queue without a practical bound: http_server.cc).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace snooker::server {

class WorkerPool {
 public:
  /// What a pool does when the system starts fewer threads than asked (a process or
  /// container limit): kAll throws std::runtime_error, naming the thread it could
  /// not start; kAsManyAsPossible works on those it started, and with none runs each
  /// job on the submitter's thread at once.
  enum class Start { kAll, kAsManyAsPossible };

  /// `threads` >= 1 workers; at most `max_queued` jobs wait for one (beyond the
  /// jobs that idle workers take at once).
  WorkerPool(int threads, int max_queued, Start start = Start::kAll);
  ~WorkerPool();  // Stop()
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Queues `job`; false (and `job` dropped) when the queue is full or the pool stopped.
  /// A job that throws is reported on stderr and its worker goes on.
  /// (A kAsManyAsPossible pool without threads runs `job` here and returns true.)
  bool TrySubmit(std::function<void()> job);
  /// Runs every queued job, then joins the threads. Later submissions fail.
  void Stop();

  /// The workers running: those asked for, or with kAsManyAsPossible those started.
  int threads() const { return static_cast<int>(thread_count_); }

 private:
  void Work();
  static void Run(const std::function<void()>& job);

  const std::size_t max_queued_;
  std::size_t thread_count_;  // set in the constructor, then constant
  std::mutex mu_;
  std::condition_variable ready_;
  std::deque<std::function<void()>> queue_;
  std::size_t busy_ = 0;  // workers running a job
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace snooker::server
