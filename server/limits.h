// Bounds of the service that are not physics: request and response sizes, message
// lengths, the wall time of a call, the worker pool, and the API's angles in degrees.
// Validation ranges of physical quantities live in physics/core/limits.h, those of a
// plan request in planner/limits.h.
//
// Why each bound: every request must cost a bounded amount of CPU, memory, time and
// output, whatever its content; docs in proto/snooker/v1/*.proto state the same values.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>

#include "physics/core/limits.h"
#include "planner/limits.h"

namespace snooker::server::limits {

using physics::Range;

// --- Angles at the API edge, in degrees (physics works in radians) ----------------
/// |cut angle| of a Collide request must stay below this, degrees (at 90 the balls
/// do not meet).
inline constexpr double kCutAngleBoundDeg = 90;
/// Heading of a shot, degrees. Accepted within ten turns either way and normalised
/// into [0, 360) before use; beyond that a heading is a client's bug, not an angle
/// (at 1e300 deg not even the turn is known: one unit in the last place is more than
/// 360 deg). At 3600 deg a unit in the last place is 5e-13 deg.
inline constexpr Range kHeadingDeg{-3600, 3600};

// --- Sizes ------------------------------------------------------------------------
/// A request message on the wire, bytes (gRPC's default receive limit, set
/// explicitly). 10 000 balls take about 320 KB.
inline constexpr std::size_t kMaxRequestBytes = 4u << 20;
/// A response message, bytes: gRPC clients refuse larger messages by default. A
/// Simulate response that would be larger is refused with RESOURCE_EXHAUSTED, saying
/// what to ask for less of.
inline constexpr std::size_t kMaxResponseBytes = 4u << 20;
/// Sampled path points in one Simulate response, all balls together (about 28 bytes
/// each on the wire); the sampling interval grows to stay within it.
inline constexpr std::int64_t kMaxPathPoints = 60'000;
/// Problems listed in one error message; the rest are counted ("and 7 more").
inline constexpr int kMaxReportedProblems = 5;
/// Bytes of a ball id quoted in an error message (longer ids are cut, with their
/// length given).
inline constexpr std::size_t kMaxQuotedIdBytes = 24;
/// An error message is never longer than this, bytes (kMaxReportedProblems problems
/// of a few hundred bytes each and the count).
inline constexpr std::size_t kMaxMessageBytes = 4096;

// --- Calls ------------------------------------------------------------------------
/// Wall time of one call: the client's deadline or this server maximum, whichever
/// comes first (`snooker serve --max-call-ms`).
inline constexpr std::chrono::milliseconds kDefaultMaxCall{10'000};
inline constexpr std::int64_t kMaxCallMsLimit = 3'600'000;
/// A gRPC connection quiet for kKeepalive gets an HTTP/2 ping; one that does not
/// answer within kKeepaliveTimeout is closed. So a client that vanished without
/// closing (a robot that lost power or its network) frees its connection within
/// 80 s rather than gRPC's default 2 h 20 s.
inline constexpr std::chrono::milliseconds kKeepalive{60'000};
inline constexpr std::chrono::milliseconds kKeepaliveTimeout{20'000};
/// Either may be set from 1 ms to a day.
inline constexpr std::chrono::milliseconds kMaxKeepalive{86'400'000};
/// `--tls-reload-s`: how often the certificate files may be read again, s (0: read
/// once at the start), at most a day.
inline constexpr std::int64_t kMaxTlsReloadSeconds = 86'400;
/// On SIGTERM/SIGINT, calls in flight may finish for this long, then are cancelled
/// (`snooker serve --shutdown-grace-ms`).
inline constexpr std::chrono::milliseconds kDefaultShutdownGrace{5'000};
inline constexpr std::int64_t kMaxShutdownGraceMs = 600'000;
/// Calls computed at once (worker threads) and calls waiting for a worker; a call
/// beyond both is refused at once with RESOURCE_EXHAUSTED (`--workers`,
/// `--max-queued`). Memory is bounded by workers x the largest call.
inline constexpr int kMaxWorkers = 256;
inline constexpr int kDefaultMaxQueued = 256;
inline constexpr int kMaxQueuedLimit = 100'000;

// --- HTTP (`snooker serve --http`) --------------------------------------------------
/// HTTP connections served at once: cpp-httplib gives each connection a thread for
/// as long as it lasts (a unary call waits there for its worker, a stream writes
/// from it); more connections wait for one. The calls themselves run on the workers.
inline constexpr int kHttpConnectionThreads = 32;
/// An idle keep-alive connection is closed after this long, s (a shutdown waits for
/// idle connections at most this long); a connection serves at most
/// kHttpKeepAliveRequests requests.
inline constexpr int kHttpKeepAliveSeconds = 2;
inline constexpr int kHttpKeepAliveRequests = 100;
/// A read or write on an HTTP connection that makes no progress for this long
/// fails, s: a client that stops reading a stream loses it; the plan goes on.
inline constexpr int kHttpIoTimeoutSeconds = 5;

// --- Vision repair ----------------------------------------------------------------
/// Overlaps and cushion overshoots up to this are repaired (balls moved, with a
/// warning), mm (`snooker serve --vision-tolerance-mm`, and the same flag of the local
/// commands). A request may ask for less, not more.
inline constexpr double kDefaultVisionToleranceMm = 1.0;
/// What the flag accepts, mm: a ball is 52.5 mm across; an error of centimetres is
/// not vision's small error but a wrong table.
inline constexpr Range kVisionToleranceMm{0, 10};

// --- Plans --------------------------------------------------------------------------
/// A Plan request without a budget gets this, ms (`--default-budget-ms`; the
/// planner's own default).
inline constexpr double kDefaultPlanBudgetMs = planner::limits::kDefaultTimeBudget * 1e3;
/// The largest budget a request may ask for, ms (`--max-budget-ms`), and what that
/// flag accepts: the planner's own range of budgets (planner/limits.h), in ms.
inline constexpr double kDefaultMaxPlanBudgetMs = 10'000;
inline constexpr Range kPlanBudgetMs{planner::limits::kTimeBudget.lo * 1e3,
                                     planner::limits::kTimeBudget.hi * 1e3};
/// Plans in the server at once, running or waiting for a worker; further Plan calls
/// are refused at once with RESOURCE_EXHAUSTED (`--max-plans`).
inline constexpr int kDefaultMaxPlans = 32;
inline constexpr int kMaxPlansLimit = 10'000;

}  // namespace snooker::server::limits
