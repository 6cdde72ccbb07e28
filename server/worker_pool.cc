#include "server/worker_pool.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace snooker::server {

WorkerPool::WorkerPool(int threads, int max_queued, Start start)
    : max_queued_(static_cast<std::size_t>(std::max(0, max_queued))),
      thread_count_(static_cast<std::size_t>(std::max(1, threads))) {
  threads_.reserve(thread_count_);
  for (std::size_t i = 0; i < thread_count_; ++i) {
    try {
      threads_.emplace_back([this] { Work(); });
    } catch (const std::system_error& e) {
      // The system has no thread to spare (a process or container limit).
      if (start == Start::kAsManyAsPossible) break;
      // The workers already started are stopped and joined, so that the error, and
      // not an abort over their joinable threads, reaches whoever asked for the pool.
      Stop();
      throw std::runtime_error("could not start worker thread " + std::to_string(i + 1) + " of " +
                               std::to_string(thread_count_) + " (" + e.what() + ")");
    } catch (...) {
      if (start == Start::kAsManyAsPossible) break;
      Stop();
      throw;
    }
  }
  thread_count_ = threads_.size();  // all of them unless kAsManyAsPossible
}

WorkerPool::~WorkerPool() { Stop(); }

bool WorkerPool::TrySubmit(std::function<void()> job) {
  if (thread_count_ == 0) {  // a pool the system gave no thread: the caller's
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (stopping_) return false;
    }
    Run(job);
    return true;
  }
  {
    std::lock_guard<std::mutex> lock(mu_);
    // Free workers take a job each at once; beyond them, at most max_queued_ wait.
    if (stopping_ || queue_.size() >= max_queued_ + (thread_count_ - busy_)) return false;
    queue_.push_back(std::move(job));
  }
  ready_.notify_one();
  return true;
}

void WorkerPool::Stop() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (stopping_ && threads_.empty()) return;
    stopping_ = true;
  }
  ready_.notify_all();
  for (std::thread& t : threads_) {
    if (t.joinable()) t.join();
  }
  threads_.clear();
}

void WorkerPool::Work() {
  for (;;) {
    std::function<void()> job;
    {
      std::unique_lock<std::mutex> lock(mu_);
      ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, and nothing left to run
      job = std::move(queue_.front());
      queue_.pop_front();
      ++busy_;
    }
    Run(job);
    job = nullptr;  // its captures go now, not at the next job
    std::lock_guard<std::mutex> lock(mu_);
    --busy_;
  }
}

// A job finishes its own call, its errors included. One that throws all the same (an
// allocation failing as it answers) is reported and the worker goes on: an exception
// out of a thread would end the process and every call in it.
void WorkerPool::Run(const std::function<void()>& job) {
  try {
    job();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "snooker: a worker's job failed: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "snooker: a worker's job failed\n");
  }
}

}  // namespace snooker::server
