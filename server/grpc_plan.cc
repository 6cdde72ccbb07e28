// The gRPC adapter's plans: Plan (unary) and PlanStream (server streaming), raw
// callback methods like the others (grpc_service.cc), with three differences:
//  * admission: at most options.max_plans plans are in the server at once (running
//    or waiting for a worker); another is refused with RESOURCE_EXHAUSTED at once;
//  * cancellation: the planner polls an atomic flag, not the context; each plan's
//    reactor sets it from OnCancel (the client cancelled, its deadline passed, or
//    the server's shutdown grace ended);
//  * the deadline: a plan stops a little before the call's deadline (kDeadlineShare
//    of the time left, within [kMinMargin, kMaxMargin]) so that its best shots so
//    far reach the client in time; with none it answers DEADLINE_EXCEEDED.
// What the planner's outcome means for the call's status is plan_api.cc's StatusOf
// alone; this file adds only what the transport owns: admission, a start after the
// deadline, and gRPC's cancellation at the client's deadline.
//
// PlanStream's writes never block the planner: a progress message is serialised on
// the planner's thread and handed to the reactor; while a write is in flight only
// the newest waits (an older one waiting is dropped and counted), and the final
// answer, when the plan ends, replaces any waiting progress and is always the last
// message. The reactor's state lives in a shared object that the worker and gRPC's
// callbacks both hold, so neither outlives what it locks; OnDone deletes the reactor.
#include <algorithm>
#include <exception>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <string>

#include "server/call_cost.h"
#include "server/decode.h"
#include "server/grpc_service.h"
#include "server/plan_api.h"
#include "server/service_detail.h"

namespace snooker::server {
namespace {

using Clock = std::chrono::steady_clock;
using service_detail::Flatten;

// The share of a plan's time (arrival to deadline) kept back for sending its answer.
constexpr double kDeadlineShare = 0.1;
constexpr auto kMinMargin = std::chrono::milliseconds(1);
constexpr auto kMaxMargin = std::chrono::milliseconds(50);

// When the planner must stop for its answer to arrive by `deadline`.
Clock::time_point PlanStop(Clock::time_point arrival, Clock::time_point deadline) {
  if (deadline == Clock::time_point::max()) return deadline;
  const auto span = deadline - arrival;
  const auto margin = std::clamp<Clock::duration>(
      std::chrono::duration_cast<Clock::duration>(span * kDeadlineShare), kMinMargin, kMaxMargin);
  return deadline - margin;
}

ApiStatus Serialize(const v1::PlanResponse& response, grpc::ByteBuffer* out) {
  if (response.ByteSizeLong() > limits::kMaxResponseBytes) {
    return {ApiStatus::Code::kResourceExhausted,
            "the answer would be larger than " + std::to_string(limits::kMaxResponseBytes) +
                " bytes; ask for fewer shots (max_shots)"};
  }
  bool own = false;
  const grpc::Status st = grpc::SerializationTraits<v1::PlanResponse>::Serialize(response, out, &own);
  if (!st.ok()) return {ApiStatus::Code::kInternal, "cannot serialise the answer: " + st.error_message()};
  return ApiStatus::Ok();
}

}  // namespace

struct ShotPlannerService::PlanCall : service_detail::CallInfo {
  const char* method = "";
  std::atomic<bool> cancel{false};  // set by the reactor's OnCancel
};

// Plan: a unary reactor whose only reactions are OnCancel (the planner's flag) and
// OnDone (itself deleted); the worker calls Finish.
class ShotPlannerService::PlanUnaryReactor final : public grpc::ServerUnaryReactor {
 public:
  explicit PlanUnaryReactor(std::shared_ptr<PlanCall> call) : call_(std::move(call)) {}
  void OnCancel() override { call_->cancel.store(true); }
  void OnDone() override { delete this; }

 private:
  std::shared_ptr<PlanCall> call_;
};

// PlanStream's reactor; see the file comment.
class ShotPlannerService::PlanStreamReactor final : public grpc::ServerWriteReactor<grpc::ByteBuffer> {
 public:
  PlanStreamReactor(ShotPlannerService* service, std::shared_ptr<PlanCall> call)
      : state_(std::make_shared<State>()) {
    state_->service = service;
    state_->call = std::move(call);
    state_->reactor = this;
  }

  // From the worker (the planner's threads, never concurrently).
  void Progress(const v1::PlanResponse& best) {
    const std::shared_ptr<State> state = state_;
    grpc::ByteBuffer bytes;
    if (!Serialize(best, &bytes).ok()) return;  // a progress message is optional
    std::lock_guard<std::mutex> lock(state->mu);
    if (state->completed || state->broken) return;
    if (state->writing) {
      if (state->pending) state->service->progress_dropped_.fetch_add(1);
      state->pending = std::move(bytes);
      return;
    }
    state->StartWrite(std::move(bytes), false);
  }

  // From the worker, once, as its last use of the reactor: the final answer (for an
  // OK status) and the status.
  void Complete(const ApiStatus& status, std::optional<grpc::ByteBuffer> final_answer) {
    const std::shared_ptr<State> state = state_;
    std::lock_guard<std::mutex> lock(state->mu);
    state->completed = true;
    state->status = ToGrpcStatus(status);
    if (state->pending) state->service->progress_dropped_.fetch_add(1);
    state->pending.reset();  // the final answer supersedes it
    if (status.ok() && !state->broken) state->final_answer = std::move(final_answer);
    if (!state->writing) state->Pump();
  }

  void OnWriteDone(bool ok) override {
    const std::shared_ptr<State> state = state_;  // the worker may drop its copy meanwhile
    std::lock_guard<std::mutex> lock(state->mu);
    state->writing = false;
    if (ok && !state->in_flight_is_final) state->service->progress_messages_.fetch_add(1);
    if (!ok) {
      // The stream is broken (the client went away, or the call was cancelled):
      // nothing more is written; the status still ends the call.
      state->broken = true;
      state->pending.reset();
      state->final_answer.reset();
    }
    state->Pump();
  }

  void OnCancel() override { state_->call->cancel.store(true); }
  void OnDone() override { delete this; }

 private:
  struct State {
    ShotPlannerService* service = nullptr;
    std::shared_ptr<PlanCall> call;
    PlanStreamReactor* reactor = nullptr;
    std::mutex mu;
    bool writing = false;             // a write is in flight
    bool in_flight_is_final = false;  // ... and it is the final answer
    bool completed = false;           // the worker is done (status set)
    bool broken = false;              // a write failed
    bool finished = false;            // Finish was called
    grpc::Status status;
    grpc::ByteBuffer in_flight;  // must live until OnWriteDone
    std::optional<grpc::ByteBuffer> pending;       // the newest progress not yet written
    std::optional<grpc::ByteBuffer> final_answer;  // the last message, once completed

    void StartWrite(grpc::ByteBuffer bytes, bool is_final) {
      in_flight = std::move(bytes);
      in_flight_is_final = is_final;
      writing = true;
      reactor->StartWrite(&in_flight);
    }
    // With mu held and no write in flight: the next write, or Finish.
    void Pump() {
      if (finished) return;
      if (completed) {
        if (final_answer && !broken) {
          grpc::ByteBuffer bytes = std::move(*final_answer);
          final_answer.reset();
          StartWrite(std::move(bytes), true);
          return;
        }
        finished = true;
        reactor->Finish(status);  // the reactor's last use here: OnDone may follow
        return;
      }
      if (pending && !broken) {
        grpc::ByteBuffer bytes = std::move(*pending);
        pending.reset();
        StartWrite(std::move(bytes), false);
      }
    }
  };
  std::shared_ptr<State> state_;
};

std::shared_ptr<ShotPlannerService::PlanCall> ShotPlannerService::AdmitPlan(
    const char* method, grpc::CallbackServerContext* context, const grpc::ByteBuffer* request,
    ApiStatus* refusal) {
  auto call = std::make_shared<PlanCall>();
  service_detail::Arrived(context, request, options_.max_call, call.get());
  call->method = method;
  if (plans_.fetch_add(1) >= options_.max_plans) {
    plans_.fetch_sub(1);
    *refusal = TooManyPlans();
  }
  return call;
}

ApiStatus ShotPlannerService::TooManyPlans() const {
  return {ApiStatus::Code::kResourceExhausted, "the server is planning " + std::to_string(options_.max_plans) +
                                                   " shots already (its --max-plans); try again later"};
}

PlanControl ShotPlannerService::PlanControlOf(Clock::time_point arrival, Clock::time_point deadline,
                                              const std::atomic<bool>* cancel) const {
  PlanControl control;
  control.deadline = PlanStop(arrival, deadline);
  control.cancel = cancel;
  control.vision_tolerance_mm = options_.vision_tolerance_mm;
  control.default_budget_ms = options_.default_plan_budget_ms;
  control.max_budget_ms = options_.max_plan_budget_ms;
  control.planner = planner_.get();
  return control;
}

ApiStatus ShotPlannerService::RunPlan(PlanCall& call, v1::PlanResponse* response, Work* work,
                                      const std::function<void(const v1::PlanResponse&)>& on_progress) {
  if (auto late = service_detail::RefuseLateStart(call, call.cancel.load() || call.context->IsCancelled(),
                                                  "the plan")) {
    work->cut_short = true;  // the clock (or a cancel) stopped all of its work
    return *late;
  }
  std::string bytes;
  if (!Flatten(*call.request, &bytes)) return ApiStatus::Invalid("cannot read the request's bytes");
  v1::PlanRequest request;
  if (ApiStatus st = ParseRequest(bytes, &request); !st.ok()) return st;
  PlanControl control = PlanControlOf(call.arrival, call.deadline, &call.cancel);
  control.on_progress = on_progress;
  ApiStatus st = server::Plan(request, response, control);
  *work = CostOf(*response);
  return service_detail::DeadlineIfClientLate(std::move(st), call);
}

grpc::ServerUnaryReactor* ShotPlannerService::Plan(grpc::CallbackServerContext* context,
                                                   const grpc::ByteBuffer* request,
                                                   grpc::ByteBuffer* response) {
  // On a gRPC thread: admit and queue the call, return at once (no exception may leave).
  received_.fetch_add(1);
  try {
    ApiStatus refusal;
    std::shared_ptr<PlanCall> call = AdmitPlan("Plan", context, request, &refusal);
    if (!refusal.ok()) {
      grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
      Record("Plan", call->peer, call->request_id, call->arrival, refusal, call->request_bytes, 0, {});
      reactor->Finish(ToGrpcStatus(refusal));
      return reactor;
    }
    auto* reactor = new PlanUnaryReactor(call);
    auto job = [this, call, reactor, response] {
      running_.fetch_add(1);
      Work work;
      std::size_t response_bytes = 0;
      const ApiStatus status = service_detail::Guarded([&] {
        v1::PlanResponse answer;
        ApiStatus st = RunPlan(*call, &answer, &work, nullptr);
        if (st.ok()) st = Serialize(answer, response);
        if (st.ok()) response_bytes = response->Length();
        return st;
      });
      running_.fetch_sub(1);
      plans_.fetch_sub(1);
      Record(call->method, call->peer, call->request_id, call->arrival, status, call->request_bytes, response_bytes, work);
      reactor->Finish(ToGrpcStatus(status));  // the last use of the reactor and the buffers
    };
    if (!pool_.TrySubmit(job)) {
      plans_.fetch_sub(1);
      const ApiStatus busy = Busy();
      Record("Plan", call->peer, call->request_id, call->arrival, busy, call->request_bytes, 0, {});
      reactor->Finish(ToGrpcStatus(busy));
    }
    return reactor;
  } catch (const std::exception& e) {  // std::bad_alloc above all
    grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
    Refuse(reactor, service_detail::CannotTake(e));
    return reactor;
  }
}

grpc::ServerWriteReactor<grpc::ByteBuffer>* ShotPlannerService::PlanStream(
    grpc::CallbackServerContext* context, const grpc::ByteBuffer* request) {
  received_.fetch_add(1);
  ApiStatus refusal;
  std::shared_ptr<PlanCall> call;
  try {
    call = AdmitPlan("PlanStream", context, request, &refusal);
  } catch (const std::exception& e) {
    refusal = service_detail::CannotTake(e);
  }
  if (!refusal.ok()) {
    // A reactor that only finishes. It needs a PlanCall for its OnCancel: the call's,
    // or one of its own when not even that could be made.
    if (call == nullptr) {
      call = std::make_shared<PlanCall>();
      call->peer = context->peer();
      call->arrival = Clock::now();
      call->request_bytes = request->Length();
    }
    auto* reactor = new PlanStreamReactor(this, call);
    Record("PlanStream", call->peer, call->request_id, call->arrival, refusal, call->request_bytes, 0, {});
    reactor->Complete(refusal, std::nullopt);
    return reactor;
  }
  auto* reactor = new PlanStreamReactor(this, call);
  auto job = [this, call, reactor] {
    running_.fetch_add(1);
    Work work;
    std::optional<grpc::ByteBuffer> final_bytes;
    std::size_t response_bytes = 0;
    const ApiStatus status = service_detail::Guarded([&] {
      v1::PlanResponse answer;
      ApiStatus st = RunPlan(*call, &answer, &work,
                                [reactor](const v1::PlanResponse& best) { reactor->Progress(best); });
      if (st.ok()) {
        final_bytes.emplace();
        st = Serialize(answer, &*final_bytes);
        if (st.ok()) response_bytes = final_bytes->Length();
      }
      return st;
    });
    running_.fetch_sub(1);
    plans_.fetch_sub(1);
    Record(call->method, call->peer, call->request_id, call->arrival, status, call->request_bytes, response_bytes, work);
    reactor->Complete(status, status.ok() ? std::move(final_bytes) : std::nullopt);
  };
  if (!pool_.TrySubmit(job)) {
    plans_.fetch_sub(1);
    const ApiStatus busy = Busy();
    Record("PlanStream", call->peer, call->request_id, call->arrival, busy, call->request_bytes, 0, {});
    reactor->Complete(busy, std::nullopt);
  }
  return reactor;
}

}  // namespace snooker::server
