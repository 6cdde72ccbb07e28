#include "server/grpc_service.h"

#include <exception>
#include <new>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "server/calibrate_api.h"
#include "server/call_cost.h"
#include "server/convert.h"
#include "server/decode.h"
#include "server/log_line.h"
#include "server/request_id.h"
#include "server/service_detail.h"

namespace snooker::server {

namespace {

grpc::StatusCode GrpcCodeOf(ApiStatus::Code code) noexcept {
  switch (code) {
    case ApiStatus::Code::kOk: return grpc::StatusCode::OK;
    case ApiStatus::Code::kInvalidArgument: return grpc::StatusCode::INVALID_ARGUMENT;
    case ApiStatus::Code::kResourceExhausted: return grpc::StatusCode::RESOURCE_EXHAUSTED;
    case ApiStatus::Code::kDeadlineExceeded: return grpc::StatusCode::DEADLINE_EXCEEDED;
    case ApiStatus::Code::kCancelled: return grpc::StatusCode::CANCELLED;
    case ApiStatus::Code::kInternal: return grpc::StatusCode::INTERNAL;
  }
  return grpc::StatusCode::UNKNOWN;
}

}  // namespace

grpc::Status ToGrpcStatus(const ApiStatus& status) noexcept {
  if (status.code == ApiStatus::Code::kOk) return grpc::Status::OK;
  try {
    return {GrpcCodeOf(status.code), status.message};
  } catch (...) {  // std::bad_alloc: an empty message is not allocated
    return {GrpcCodeOf(status.code), std::string()};
  }
}

const char* StatusCodeName(grpc::StatusCode code) {
  static constexpr const char* kNames[] = {
      "OK",           "CANCELLED",          "UNKNOWN",           "INVALID_ARGUMENT",
      "DEADLINE_EXCEEDED", "NOT_FOUND",     "ALREADY_EXISTS",    "PERMISSION_DENIED",
      "RESOURCE_EXHAUSTED", "FAILED_PRECONDITION", "ABORTED",    "OUT_OF_RANGE",
      "UNIMPLEMENTED", "INTERNAL",          "UNAVAILABLE",       "DATA_LOSS",
      "UNAUTHENTICATED"};
  const auto i = static_cast<std::size_t>(code);
  return i < std::size(kNames) ? kNames[i] : "UNKNOWN";
}

namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

namespace service_detail {

Clock::time_point CallDeadline(std::chrono::system_clock::time_point client, Clock::time_point arrival,
                               std::chrono::milliseconds max_call) {
  const Clock::time_point server_bound = arrival + max_call;
  const auto system_now = std::chrono::system_clock::now();
  // Compared before subtracting: a deadline far in the future must not overflow.
  if (client >= system_now + max_call) return server_bound;
  const auto left = std::chrono::duration_cast<Clock::duration>(client - system_now);
  return std::min(server_bound, Clock::now() + left);
}

// gRPC cancels a call when the client's deadline passes, with timers of a millisecond
// grain: a cancellation within a few milliseconds of that deadline is the deadline.
constexpr auto kTimerGrain = std::chrono::milliseconds(2);

bool ClientDeadlinePassed(std::chrono::system_clock::time_point client) {
  return client != std::chrono::system_clock::time_point::max() &&
         std::chrono::system_clock::now() + kTimerGrain >= client;
}

bool IsCancelled(void* context) {
  return static_cast<grpc::CallbackServerContext*>(context)->IsCancelled();
}

// Requests are at most limits::kMaxRequestBytes: gRPC refuses larger ones before
// they get here.
bool Flatten(const grpc::ByteBuffer& buffer, std::string* out) {
  std::vector<grpc::Slice> slices;
  if (!buffer.Dump(&slices).ok()) return false;
  out->clear();
  out->reserve(buffer.Length());
  for (const grpc::Slice& s : slices) out->append(reinterpret_cast<const char*>(s.begin()), s.size());
  return true;
}

ApiStatus CannotTake(const std::exception& e) {
  return {ApiStatus::Code::kResourceExhausted, std::string("the server cannot take the call: ") + e.what()};
}

std::optional<ApiStatus> RefuseLateStart(const CallInfo& call, bool cancelled, const char* what) {
  const auto waited_ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - call.arrival).count();
  const std::string waited = " (" + std::to_string(waited_ms) + " ms waiting for a worker)";
  if (Clock::now() >= call.deadline || (cancelled && ClientDeadlinePassed(call.client_deadline))) {
    return ApiStatus{ApiStatus::Code::kDeadlineExceeded,
                     std::string("the call's deadline passed before ") + what + " started" + waited};
  }
  if (cancelled) {
    return ApiStatus{ApiStatus::Code::kCancelled,
                     std::string("the call was cancelled before ") + what + " started" + waited};
  }
  return std::nullopt;
}

ApiStatus DeadlineIfClientLate(ApiStatus status, const CallInfo& call) {
  if (status.code == ApiStatus::Code::kCancelled && ClientDeadlinePassed(call.client_deadline)) {
    status.code = ApiStatus::Code::kDeadlineExceeded;
    status.message = "the client's deadline passed: " + status.message;
  }
  return status;
}

void Arrived(grpc::CallbackServerContext* context, const grpc::ByteBuffer* request,
             std::chrono::milliseconds max_call, CallInfo* info) {
  info->context = context;
  info->request = request;
  info->peer = context->peer();
  const auto& metadata = context->client_metadata();
  const auto given = metadata.find(grpc::string_ref(kRequestIdMetadata.data(), kRequestIdMetadata.size()));
  info->request_id =
      RequestIdFor(given == metadata.end() ? std::string_view() : std::string_view(given->second.data(), given->second.size()));
  context->AddInitialMetadata(std::string(kRequestIdMetadata), info->request_id);
  info->arrival = Clock::now();
  info->client_deadline = context->deadline();
  info->deadline = CallDeadline(info->client_deadline, info->arrival, max_call);
  info->request_bytes = request->Length();
}

}  // namespace service_detail

namespace {

using service_detail::ClientDeadlinePassed;
using service_detail::Flatten;
using service_detail::IsCancelled;

// Parse, run, serialise: one method of the service on raw bytes.
template <typename Request, typename Response,
          ApiStatus (*Operation)(const Request&, Response*, const CallLimits&)>
ApiStatus RunMethod(std::string_view bytes, const CallLimits& limits, grpc::ByteBuffer* out,
                    ShotPlannerService::Work* work) {
  Request request;
  if (ApiStatus st = ParseRequest(bytes, &request); !st.ok()) return st;
  Response response;
  if (ApiStatus st = Operation(request, &response, limits); !st.ok()) return st;
  *work = CostOf(response);
  bool own = false;
  const grpc::Status st = grpc::SerializationTraits<Response>::Serialize(response, out, &own);
  if (!st.ok()) return {ApiStatus::Code::kInternal, "cannot serialise the response: " + st.error_message()};
  return ApiStatus::Ok();
}

constexpr ShotPlannerService::Method kCollide{
    "Collide", &RunMethod<v1::CollideRequest, v1::CollideResponse, &server::Collide>};
constexpr ShotPlannerService::Method kSimulate{
    "Simulate", &RunMethod<v1::SimulateRequest, v1::SimulateResponse, &server::Simulate>};
constexpr ShotPlannerService::Method kGetModel{
    "GetModel", &RunMethod<v1::GetModelRequest, v1::GetModelResponse, &server::GetModel>};
constexpr ShotPlannerService::Method kCalibrate{
    "Calibrate", &RunMethod<v1::CalibrateRequest, v1::CalibrateResponse, &server::Calibrate>};

}  // namespace

struct ShotPlannerService::Call : service_detail::CallInfo {
  const Method* method = nullptr;
  grpc::ByteBuffer* response = nullptr;
  grpc::ServerUnaryReactor* reactor = nullptr;
};

std::string ValidateServiceOptions(const ServiceOptions& o) {
  std::string out;
  auto check = [&](bool ok, const std::string& what) {
    if (!ok) out += (out.empty() ? "" : "; ") + what;
  };
  check(o.max_call.count() >= 1 && o.max_call.count() <= limits::kMaxCallMsLimit,
        "max_call " + std::to_string(o.max_call.count()) + " ms is outside [1, " +
            std::to_string(limits::kMaxCallMsLimit) + "] ms");
  check(o.workers >= 0 && o.workers <= limits::kMaxWorkers,
        "workers " + std::to_string(o.workers) + " is outside [0, " +
            std::to_string(limits::kMaxWorkers) + "]");
  check(o.max_queued >= 0 && o.max_queued <= limits::kMaxQueuedLimit,
        "max_queued " + std::to_string(o.max_queued) + " is outside [0, " +
            std::to_string(limits::kMaxQueuedLimit) + "]");
  check(limits::kVisionToleranceMm.Contains(o.vision_tolerance_mm),
        "vision_tolerance_mm " + FormatNumber(o.vision_tolerance_mm) + " is outside [" +
            FormatNumber(limits::kVisionToleranceMm.lo) + ", " +
            FormatNumber(limits::kVisionToleranceMm.hi) + "] mm");
  check(limits::kPlanBudgetMs.Contains(o.max_plan_budget_ms),
        "max_plan_budget_ms " + FormatNumber(o.max_plan_budget_ms) + " is outside [" +
            FormatNumber(limits::kPlanBudgetMs.lo) + ", " + FormatNumber(limits::kPlanBudgetMs.hi) +
            "] ms");
  check(limits::kPlanBudgetMs.Contains(o.default_plan_budget_ms) &&
            o.default_plan_budget_ms <= o.max_plan_budget_ms,
        "default_plan_budget_ms " + FormatNumber(o.default_plan_budget_ms) + " is outside [" +
            FormatNumber(limits::kPlanBudgetMs.lo) + ", max_plan_budget_ms " +
            FormatNumber(o.max_plan_budget_ms) + "] ms");
  check(o.max_plans >= 1 && o.max_plans <= limits::kMaxPlansLimit,
        "max_plans " + std::to_string(o.max_plans) + " is outside [1, " +
            std::to_string(limits::kMaxPlansLimit) + "]");
  return out;
}

ShotPlannerService::ShotPlannerService(const ServiceOptions& options)
    : options_(options),
      pool_(options.workers > 0 ? options.workers
                                : static_cast<int>(std::max(1u, std::thread::hardware_concurrency())),
            options.max_queued) {
  CallLimits limits;
  limits.vision_tolerance_mm = options.vision_tolerance_mm;
  limits.default_plan_budget_ms = options.default_plan_budget_ms;
  limits.max_plan_budget_ms = options.max_plan_budget_ms;
  service_limits_ = DefaultServiceLimits(limits);
  service_limits_.set_max_call_ms(options.max_call.count());
  service_limits_.set_max_plans(options.max_plans);
  service_limits_.set_workers(pool_.threads());
  service_limits_.set_max_queued(options.max_queued);
  if (options_.model) {
    planner_ = std::make_unique<planner::Planner>(planner::PlannerConfig{}.WithModel(*options_.model));
  }
}

ShotPlannerService::~ShotPlannerService() { pool_.Stop(); }

grpc::ServerUnaryReactor* ShotPlannerService::Collide(grpc::CallbackServerContext* context,
                                                      const grpc::ByteBuffer* request,
                                                      grpc::ByteBuffer* response) {
  return Accept(kCollide, context, request, response);
}

grpc::ServerUnaryReactor* ShotPlannerService::Simulate(grpc::CallbackServerContext* context,
                                                       const grpc::ByteBuffer* request,
                                                       grpc::ByteBuffer* response) {
  return Accept(kSimulate, context, request, response);
}

grpc::ServerUnaryReactor* ShotPlannerService::GetModel(grpc::CallbackServerContext* context,
                                                       const grpc::ByteBuffer* request,
                                                       grpc::ByteBuffer* response) {
  return Accept(kGetModel, context, request, response);
}

grpc::ServerUnaryReactor* ShotPlannerService::Calibrate(grpc::CallbackServerContext* context,
                                                        const grpc::ByteBuffer* request,
                                                        grpc::ByteBuffer* response) {
  return Accept(kCalibrate, context, request, response);
}

grpc::ServerUnaryReactor* ShotPlannerService::Accept(const Method& method,
                                                     grpc::CallbackServerContext* context,
                                                     const grpc::ByteBuffer* request,
                                                     grpc::ByteBuffer* response) {
  // On a gRPC thread: queue the call and return at once (no blocking here, and no
  // exception may leave).
  received_.fetch_add(1);
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  try {
    auto call = std::make_shared<Call>();
    service_detail::Arrived(context, request, options_.max_call, call.get());
    call->method = &method;
    call->response = response;
    call->reactor = reactor;
    if (!pool_.TrySubmit([this, call] { Run(call); })) {
      Finish(*call, Busy(), 0, {});
    }
  } catch (const std::exception& e) {  // std::bad_alloc above all
    Refuse(reactor, service_detail::CannotTake(e));
  }
  return reactor;
}

void ShotPlannerService::Run(const std::shared_ptr<Call>& call) {
  running_.fetch_add(1);
  ApiStatus status;
  std::size_t response_bytes = 0;
  Work work;
  if (auto late = service_detail::RefuseLateStart(*call, call->context->IsCancelled(), "it")) {
    status = std::move(*late);
  } else {
    CallLimits limits = LimitsOf(call->deadline);
    limits.interrupt.poll = &IsCancelled;
    limits.interrupt.poll_context = call->context;
    status = service_detail::Guarded([&]() -> ApiStatus {
      std::string bytes;
      if (!Flatten(*call->request, &bytes)) return ApiStatus::Invalid("cannot read the request's bytes");
      ApiStatus result = service_detail::DeadlineIfClientLate(
          call->method->run(bytes, limits, call->response, &work), *call);
      if (result.ok()) response_bytes = call->response->Length();
      return result;
    });
  }
  running_.fetch_sub(1);
  Finish(*call, status, response_bytes, work);
}

CallLimits ShotPlannerService::LimitsOf(Clock::time_point deadline) const {
  CallLimits limits;
  limits.interrupt.deadline = deadline;
  limits.vision_tolerance_mm = options_.vision_tolerance_mm;
  limits.default_plan_budget_ms = options_.default_plan_budget_ms;
  limits.max_plan_budget_ms = options_.max_plan_budget_ms;
  limits.service = &service_limits_;
  limits.model = model();
  return limits;
}

ApiStatus ShotPlannerService::Busy() const {
  return {ApiStatus::Code::kResourceExhausted,
          "the server is busy: " + std::to_string(pool_.threads()) + " calls running and " +
              std::to_string(options_.max_queued) + " waiting; try again later"};
}

void ShotPlannerService::Finish(Call& call, const ApiStatus& status, std::size_t response_bytes,
                                const Work& work) {
  // Counted and logged first: a client that has its answer sees it counted.
  Record(call.method->name, call.peer, call.request_id, call.arrival, status, call.request_bytes, response_bytes, work);
  // The context and buffers belong to gRPC once Finish is called: nothing of them
  // is touched after it.
  call.reactor->Finish(ToGrpcStatus(status));
}

void ShotPlannerService::Refuse(grpc::ServerUnaryReactor* reactor, const ApiStatus& status) {
  Count(status);
  reactor->Finish(ToGrpcStatus(status));
}

void ShotPlannerService::Count(const ApiStatus& status) noexcept {
  by_status_[static_cast<std::size_t>(GrpcCodeOf(status.code)) % by_status_.size()].fetch_add(1);
  finished_.fetch_add(1);
}

void ShotPlannerService::Record(const char* method, const std::string& peer, const std::string& request_id,
                                Clock::time_point arrival,
                                const ApiStatus& status, std::size_t request_bytes,
                                std::size_t response_bytes, const Work& work, const std::string& extra) noexcept {
  const double latency_ms = std::chrono::duration<double, std::milli>(Clock::now() - arrival).count();
  // Observed before it is counted as finished: a reader that sees it finished sees
  // it in its method's counts too.
  metrics_.Observe(MethodIndex(method), static_cast<int>(GrpcCodeOf(status.code)), latency_ms * 1e-3);
  if (work.cut_short) plans_cut_short_.fetch_add(1);
  // Logged before it is counted as finished too: a reader that sees it finished finds
  // its line (or its loss). The call is answered after this, whatever becomes of its line.
  if (options_.log != nullptr) {
    const bool written = WriteLogLine(*options_.log, log_mu_, [&](std::ostream& line) {
      line << "snooker: call method=" << method << " peer=" << peer << " request_id=" << request_id
           << " status=" << ToString(status.code)
           << " latency_ms=" << latency_ms << " simulations=" << work.simulations
           << " request_bytes=" << request_bytes << " response_bytes=" << response_bytes
           << (work.cut_short ? " cut_short=1" : "") << extra << "\n";
    });
    if (!written) log_lines_lost_.fetch_add(1);
  }
  Count(status);
}

CallCounts ShotPlannerService::counts() const {
  CallCounts c;
  // finished before received: a snapshot never shows more finished than received.
  c.finished = finished_.load();
  for (std::size_t i = 0; i < by_status_.size(); ++i) c.by_status[i] = by_status_[i].load();
  c.running = running_.load();
  c.plans = plans_.load();
  c.progress_messages = progress_messages_.load();
  c.progress_dropped = progress_dropped_.load();
  c.log_lines_lost = log_lines_lost_.load();
  c.plans_cut_short = plans_cut_short_.load();
  c.methods = metrics_.Read();
  c.received = received_.load();
  return c;
}

}  // namespace snooker::server
