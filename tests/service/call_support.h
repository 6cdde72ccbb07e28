// Many gRPC calls at once, and a measure of how many make a given amount of work,
// for the tests that show a server stop working early (deadlines, cancellation,
// shutdown) without timing anything tighter than a generous bound.
#pragma once

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "server/api.h"
#include "snooker/v1/service.grpc.pb.h"
#include "tests/service/requests.h"

namespace snooker::call_support {

/// Total work given to a server when a test shows it stopped early; the bound such a
/// test asserts is at most half of it.
inline constexpr auto kWork = std::chrono::seconds(8);

/// How many calls of testing_requests::Heavy() make kWork for one worker, measured
/// from calls through the library (so the tests hold on a slow sanitizer build as on
/// a fast one): the fastest of three, since a call slowed by a busy machine (ctest
/// runs tests side by side) would give too few calls to outlast the test's signal.
inline int HeavyCallsForTheWork() {
  using Clock = std::chrono::steady_clock;
  Clock::duration one = Clock::duration::max();
  for (int k = 0; k < 3; ++k) {
    const auto t0 = Clock::now();
    v1::SimulateResponse resp;
    EXPECT_TRUE(server::Simulate(testing_requests::Heavy(), &resp).ok());
    one = std::min(one, Clock::now() - t0);
  }
  one = std::max<Clock::duration>(one, std::chrono::microseconds(100));
  return static_cast<int>(std::clamp<std::int64_t>(kWork / one + 1, 20, 4000));
}

/// Many Simulate calls at once through the callback stub, and their statuses.
class Batch {
 public:
  Batch(v1::ShotPlanner::Stub* stub, const v1::SimulateRequest& request, int n,
        std::optional<std::chrono::milliseconds> deadline) {
    for (int i = 0; i < n; ++i) {
      calls_.push_back(std::make_unique<Call>());
      Call& c = *calls_.back();
      if (deadline) c.context.set_deadline(std::chrono::system_clock::now() + *deadline);
      stub->async()->Simulate(&c.context, &request, &c.response, [this, &c](grpc::Status s) {
        std::lock_guard<std::mutex> lock(mu_);
        c.status = std::move(s);
        ++done_;
        cv_.notify_all();
      });
    }
  }
  ~Batch() { Wait(); }  // the callbacks use this object

  void CancelAll() {
    for (auto& c : calls_) c->context.TryCancel();
  }
  /// Answers so far.
  std::size_t done() {
    std::lock_guard<std::mutex> lock(mu_);
    return done_;
  }
  /// Waits for every answer (at most 60 s); counts by status code.
  std::vector<int> Wait() {
    std::unique_lock<std::mutex> lock(mu_);
    cv_.wait_for(lock, std::chrono::seconds(60), [&] { return done_ == calls_.size(); });
    EXPECT_EQ(done_, calls_.size());
    std::vector<int> by_code(17, 0);
    for (const auto& c : calls_) ++by_code[static_cast<std::size_t>(c->status.error_code())];
    return by_code;
  }
  const grpc::Status& status(std::size_t i) const { return calls_[i]->status; }

 private:
  struct Call {
    grpc::ClientContext context;
    v1::SimulateResponse response;
    grpc::Status status;
  };
  std::vector<std::unique_ptr<Call>> calls_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::size_t done_ = 0;
};

}  // namespace snooker::call_support
