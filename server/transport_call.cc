// Calls of another transport in the same process (the HTTP adapter): they take the
// gRPC methods' path through the service (grpc_service.h, Submit): the plan
// admission, the worker pool and its queue, the refusal of a call whose deadline
// passed while it waited, the counters and the log line. Only the bytes in and out
// and the cancellation (an atomic flag the transport sets) are the transport's.
#include <exception>
#include <utility>

#include "server/grpc_service.h"
#include "server/service_detail.h"

namespace snooker::server {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

Clock::time_point ShotPlannerService::DeadlineOf(Clock::time_point arrival,
                                                 std::optional<std::chrono::milliseconds> timeout) const {
  if (timeout && *timeout < options_.max_call) return arrival + *timeout;
  return arrival + options_.max_call;
}

void ShotPlannerService::CountProgress(bool written) {
  (written ? progress_messages_ : progress_dropped_).fetch_add(1);
}

void ShotPlannerService::Submit(std::shared_ptr<TransportCall> call, TransportWork work,
                                std::function<void(const ApiStatus&)> done) {
  received_.fetch_add(1);
  auto refuse = [&](const ApiStatus& status) {
    Record(call->method.c_str(), call->peer, call->request_id, call->arrival, status, call->request_bytes, 0, {},
           call->log_extra);
    done(status);
  };
  bool plan_counted = false;
  try {
    if (call->is_plan) {
      plan_counted = true;
      if (plans_.fetch_add(1) >= options_.max_plans) {
        plans_.fetch_sub(1);
        plan_counted = false;
        refuse(TooManyPlans());
        return;
      }
    }
    auto job = [this, call, work = std::move(work), done] {
      running_.fetch_add(1);
      Work did;
      std::size_t response_bytes = 0;
      service_detail::CallInfo info;
      info.arrival = call->arrival;
      info.deadline = call->deadline;
      info.client_deadline = std::chrono::system_clock::time_point::max();  // ours is `deadline`
      ApiStatus status;
      if (auto late = service_detail::RefuseLateStart(info, call->cancel.load(), call->is_plan ? "the plan" : "it")) {
        status = std::move(*late);
        did.cut_short = call->is_plan;  // the clock (or a cancel) stopped all of its work
      } else {
        status = service_detail::Guarded([&] {
          CallLimits limits = LimitsOf(call->deadline);
          limits.interrupt.cancelled = &call->cancel;
          return work(limits, PlanControlOf(call->arrival, call->deadline, &call->cancel), &did,
                      &response_bytes);
        });
      }
      running_.fetch_sub(1);
      if (call->is_plan) plans_.fetch_sub(1);
      Record(call->method.c_str(), call->peer, call->request_id, call->arrival, status, call->request_bytes,
             status.ok() ? response_bytes : 0, did, call->log_extra);
      done(status);
    };
    if (!pool_.TrySubmit(std::move(job))) {
      if (plan_counted) plans_.fetch_sub(1);
      plan_counted = false;
      refuse(Busy());
    }
  } catch (const std::exception& e) {  // std::bad_alloc above all, before the job was queued
    if (plan_counted) plans_.fetch_sub(1);
    refuse(service_detail::CannotTake(e));
  }
}

}  // namespace snooker::server
