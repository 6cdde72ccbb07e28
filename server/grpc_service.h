// The gRPC adapter: request bytes in -> decode.h, api.h call -> response bytes and
// status out. No logic about the physics here; what is here is about calls:
//  * Raw requests: each method takes the grpc::ByteBuffer and parses it itself
//    (decode.h), so bytes that do not parse answer INVALID_ARGUMENT with a reason
//    (the generated service would answer INTERNAL with no message).
//  * Callback API with a worker pool (worker_pool.h): gRPC's threads only queue a
//    call; `workers` threads compute, at most `max_queued` calls wait, a call beyond
//    that is refused with RESOURCE_EXHAUSTED at once.
//  * Wall time: every call's deadline is the client's or arrival + max_call,
//    whichever is first; it and the client's cancellation (ServerContext::
//    IsCancelled) are checked before a call starts and inside long runs
//    (physics::Interrupt). Stopped calls answer DEADLINE_EXCEEDED or CANCELLED.
//  * One log line per call (method, peer, request id, status, latency, simulations,
//    bytes) and counters; the request id (request_id.h) also goes back to the client.
//  * Plans (Plan, PlanStream; grpc_plan.cc) run on the same workers, at most
//    max_plans in the server at once (more are refused with RESOURCE_EXHAUSTED at
//    once). Their reactors turn gRPC's cancellation (the client's, its deadline's, a
//    shutdown's) into the planner's cancel flag; a plan stops a little before the
//    call's deadline so that its best shots so far reach the client in time.
//    PlanStream writes from the planner's threads without blocking them: while a
//    write is in flight only the newest progress message waits (older ones are
//    dropped), and the final answer is always the last message.
//  * Another transport in the same process (the HTTP adapter) runs its calls here
//    too (Submit): one pool of workers, one admission, one log.
#pragma once

#include <grpcpp/grpcpp.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>

#include "server/api.h"
#include "server/api_status.h"
#include "server/call_cost.h"
#include "server/limits.h"
#include "server/metrics.h"
#include "server/plan_api.h"
#include "server/worker_pool.h"
#include "snooker/v1/plan.pb.h"
#include "snooker/v1/service.grpc.pb.h"

namespace snooker::server {

/// An API status as a gRPC status with its message (the only place that maps the
/// codes). Never throws, as a call must always be finished: when the message cannot
/// be copied (no memory), the status goes without it.
grpc::Status ToGrpcStatus(const ApiStatus& status) noexcept;

/// gRPC's name of a status code ("OK", "INVALID_ARGUMENT", ...; "UNKNOWN" for a
/// value out of range).
const char* StatusCodeName(grpc::StatusCode code);

struct ServiceOptions {
  /// Longest wall time of a call (and the default deadline of a call without one).
  std::chrono::milliseconds max_call = limits::kDefaultMaxCall;
  /// Calls computed at once; 0: one per hardware thread.
  int workers = 0;
  /// Calls waiting for a worker.
  int max_queued = limits::kDefaultMaxQueued;
  /// Where to write one line per finished call; nullptr: nowhere.
  std::ostream* log = nullptr;
  /// The vision repair's tolerance, mm: a request's default and its largest.
  double vision_tolerance_mm = limits::kDefaultVisionToleranceMm;
  /// A plan's budget when its request sets none, and the largest allowed, ms.
  double default_plan_budget_ms = limits::kDefaultPlanBudgetMs;
  double max_plan_budget_ms = limits::kDefaultMaxPlanBudgetMs;
  /// Plans in the server at once (running or waiting); more are refused at once.
  int max_plans = limits::kDefaultMaxPlans;
  /// The physical model every call simulates and plans with (`--model FILE`);
  /// none: the default model.
  std::optional<physics::Model> model;
};

/// Empty when the options are within their ranges (server/limits.h); otherwise
/// what is wrong, naming the option.
std::string ValidateServiceOptions(const ServiceOptions& options);

/// Counts of calls, for tests and monitoring (a snapshot).
struct CallCounts {
  std::int64_t received = 0;  ///< calls that reached a method
  std::int64_t finished = 0;  ///< calls answered (any status)
  std::int64_t running = 0;   ///< calls on a worker right now
  std::int64_t plans = 0;     ///< Plan and PlanStream calls in the server right now
  std::int64_t progress_messages = 0;  ///< PlanStream progress messages written
  std::int64_t progress_dropped = 0;   ///< ... and replaced by newer ones before a write
  std::int64_t log_lines_lost = 0;     ///< call log lines the log stream refused (the calls still finished)
  std::int64_t plans_cut_short = 0;    ///< plans the clock or a cancel stopped before their cap (CallCost)
  /// Finished calls by grpc::StatusCode (0 OK ... 16 UNAUTHENTICATED).
  std::array<std::int64_t, kStatusCodeCount> by_status{};
  /// Answered calls by method (kMethodNames): statuses and latencies.
  std::array<MethodCounts, kMethodCount> methods{};
  std::int64_t in_flight() const { return received - finished; }
  std::int64_t with(grpc::StatusCode code) const { return by_status[static_cast<size_t>(code)]; }
};

using ShotPlannerRawService = v1::ShotPlanner::WithRawCallbackMethod_Collide<
    v1::ShotPlanner::WithRawCallbackMethod_Simulate<v1::ShotPlanner::WithRawCallbackMethod_GetModel<
        v1::ShotPlanner::WithRawCallbackMethod_Plan<v1::ShotPlanner::WithRawCallbackMethod_PlanStream<
            v1::ShotPlanner::WithRawCallbackMethod_Calibrate<v1::ShotPlanner::Service>>>>>>;

class ShotPlannerService final : public ShotPlannerRawService {
 public:
  explicit ShotPlannerService(const ServiceOptions& options);
  ~ShotPlannerService() override;

  grpc::ServerUnaryReactor* Collide(grpc::CallbackServerContext* context,
                                    const grpc::ByteBuffer* request,
                                    grpc::ByteBuffer* response) override;
  grpc::ServerUnaryReactor* Simulate(grpc::CallbackServerContext* context,
                                     const grpc::ByteBuffer* request,
                                     grpc::ByteBuffer* response) override;
  grpc::ServerUnaryReactor* GetModel(grpc::CallbackServerContext* context,
                                     const grpc::ByteBuffer* request,
                                     grpc::ByteBuffer* response) override;
  grpc::ServerUnaryReactor* Plan(grpc::CallbackServerContext* context,
                                 const grpc::ByteBuffer* request,
                                 grpc::ByteBuffer* response) override;
  grpc::ServerWriteReactor<grpc::ByteBuffer>* PlanStream(grpc::CallbackServerContext* context,
                                                         const grpc::ByteBuffer* request) override;
  grpc::ServerUnaryReactor* Calibrate(grpc::CallbackServerContext* context, const grpc::ByteBuffer* request,
                                      grpc::ByteBuffer* response) override;

  CallCounts counts() const;
  /// The lock of options.log: every line of the process's transports is written
  /// under it (WriteLogLine), so that lines of gRPC and HTTP calls never interleave.
  std::mutex& log_mutex() { return log_mu_; }
  /// Runs what is queued and joins the workers. Call after grpc::Server::Shutdown
  /// returned (every call then has an answer).
  void StopWorkers() { pool_.Stop(); }

  /// What a call did, for its log line and the metrics.
  using Work = CallCost;

  // --- Calls of another transport in this process (the HTTP adapter, http_server.h):
  // the same workers, admission, limits, counters and log as the gRPC methods. ------
  /// One such call.
  struct TransportCall {
    std::string method;  ///< the procedure ("Plan"), for the log
    std::string peer;    ///< who sent it ("ipv4:127.0.0.1:51000"), for the log
    std::string request_id;  ///< its name in the log and the answer (request_id.h)
    std::chrono::steady_clock::time_point arrival;
    std::chrono::steady_clock::time_point deadline;  ///< when it must end (DeadlineOf)
    std::size_t request_bytes = 0;
    /// A plan: counted among max_plans, and stopped a little before its deadline so
    /// that its best shots so far reach the client in time.
    bool is_plan = false;
    /// Set by the transport to stop the call: its client went away, or the
    /// shutdown's grace ended.
    std::atomic<bool> cancel{false};
    std::string log_extra;  ///< appended to the log line (" transport=http")
  };
  /// A transport call's work, on a worker: with the server's limits and the call's
  /// deadline and cancellation (`limits` for the unary operations, `plan` for a
  /// plan's); `work` and `response_bytes` are for the log.
  using TransportWork = std::function<ApiStatus(const CallLimits& limits, const PlanControl& plan,
                                                Work* work, std::size_t* response_bytes)>;
  /// Runs `work` on the workers as a gRPC call is run: refused at once with
  /// RESOURCE_EXHAUSTED when max_plans plans are in the server (a plan) or the
  /// workers and queue are full; DEADLINE_EXCEEDED or CANCELLED when its deadline
  /// passed or it was cancelled while it waited; counted and logged. `done` gets the
  /// status exactly once, after the log line: on the worker, or on this thread when
  /// the call is refused.
  void Submit(std::shared_ptr<TransportCall> call, TransportWork work,
              std::function<void(const ApiStatus&)> done);
  /// When a call that arrived at `arrival` must end: after the client's `timeout`
  /// (none: no deadline of its own) or the server's max_call, whichever is first.
  std::chrono::steady_clock::time_point DeadlineOf(std::chrono::steady_clock::time_point arrival,
                                                   std::optional<std::chrono::milliseconds> timeout) const;
  /// Counts a streamed progress message of another transport: written, or dropped
  /// for a newer one.
  void CountProgress(bool written);
  /// One unary method: parse the request, run the operation, serialise the answer.
  /// (Plan and PlanStream have their own path: grpc_plan.cc.)
  struct Method {
    const char* name;
    ApiStatus (*run)(std::string_view request, const CallLimits& limits,
                     grpc::ByteBuffer* response, Work* work);
  };

 private:
  struct Call;
  struct PlanCall;
  class PlanUnaryReactor;
  class PlanStreamReactor;
  grpc::ServerUnaryReactor* Accept(const Method& method, grpc::CallbackServerContext* context,
                                   const grpc::ByteBuffer* request, grpc::ByteBuffer* response);
  void Run(const std::shared_ptr<Call>& call);
  void Finish(Call& call, const ApiStatus& status, std::size_t response_bytes, const Work& work);
  /// Answers a call that could not be taken at all (counted, not logged: the log
  /// line may be what memory cannot afford).
  void Refuse(grpc::ServerUnaryReactor* reactor, const ApiStatus& status);
  /// The answer to a call that finds every worker busy and the queue full.
  ApiStatus Busy() const;
  /// The answer to a plan that finds max_plans plans in the server.
  ApiStatus TooManyPlans() const;
  /// The limits of a call that ends at `deadline`: the server's flags and model.
  CallLimits LimitsOf(std::chrono::steady_clock::time_point deadline) const;
  /// The control of a plan that arrived at `arrival` and ends at `deadline` (it
  /// stops a little before), stopped by `cancel`: the server's flags and planner.
  PlanControl PlanControlOf(std::chrono::steady_clock::time_point arrival,
                            std::chrono::steady_clock::time_point deadline,
                            const std::atomic<bool>* cancel) const;
  /// Counts a finished call by its status.
  void Count(const ApiStatus& status) noexcept;
  /// Counts a finished call and writes its log line (a line the log refuses is
  /// counted in log_lines_lost, never thrown: the call's answer comes after this).
  void Record(const char* method, const std::string& peer, const std::string& request_id,
              std::chrono::steady_clock::time_point arrival,
              const ApiStatus& status, std::size_t request_bytes, std::size_t response_bytes,
              const Work& work, const std::string& extra = "") noexcept;
  /// Plans: a new PlanCall for a call that arrived (with `refusal` set when max_plans
  /// are in the server), the plan itself on a worker, and its status.
  std::shared_ptr<PlanCall> AdmitPlan(const char* method, grpc::CallbackServerContext* context,
                                      const grpc::ByteBuffer* request, ApiStatus* refusal);
  ApiStatus RunPlan(PlanCall& call, v1::PlanResponse* response, Work* work,
                    const std::function<void(const v1::PlanResponse&)>& on_progress);

  ServiceOptions options_;
  v1::ServiceLimits service_limits_;  // what GetModel reports
  /// The planner of options_.model (nullptr: the default planner, shared).
  std::unique_ptr<planner::Planner> planner_;
  const physics::Model* model() const { return options_.model ? &*options_.model : nullptr; }
  std::atomic<std::int64_t> received_{0}, finished_{0}, running_{0}, plans_{0};
  std::atomic<std::int64_t> progress_messages_{0}, progress_dropped_{0}, log_lines_lost_{0},
      plans_cut_short_{0};
  std::array<std::atomic<std::int64_t>, kStatusCodeCount> by_status_{};
  MethodMetrics metrics_;
  std::mutex log_mu_;
  WorkerPool pool_;  // last: its threads use the members above
};

}  // namespace snooker::server
