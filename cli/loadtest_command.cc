// snooker loadtest: an offline load test of a `snooker serve` on this machine. C
// client threads, each with a connection of its own, send N calls in all (built-in
// varied tables, or a folder of table files), time each, and check every answer.
// Bounded in count (N), concurrency and time (--max-seconds: no call is sent after
// it), and it sends load only to a loopback address.
#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>

#include "cli/args.h"
#include "cli/client.h"
#include "cli/commands.h"
#include "cli/json.h"
#include "cli/load_tables.h"
#include "server/address.h"
#include "server/convert.h"
#include "snooker/v1/service.grpc.pb.h"

namespace snooker::cli {
namespace {

constexpr const char* kLoadtestHelp = R"(usage: snooker loadtest --target 127.0.0.1:PORT --concurrency C --requests N
                        [--method simulate|plan] [--budget-ms MS] [--tables DIR] [--seed S]
                        [--max-seconds S] [--json] [--tls-ca CA.pem ...] [--deadline-ms MS]

Sends N calls to a snooker server on this machine from C client threads (each with
its own connection), then prints throughput, latency percentiles, the calls by
status code and the problems found in the answers. Every answer is checked: for
simulate, every ball of the table answered once, finite, on or near the table,
events in time order naming the table's balls, and each vision repair within the
server's tolerance (GetModel); for plan, the final answer with at most the shots
asked for, each inside the request's limits (speed in [min, max], |topspin| and
|sidespin| within their fractions of the rolling spin), its probability in [0, 1]
and its position value in [0, 1.48], naming the table's balls, events in time
order, repairs within the tolerance, and a reason when there is no shot. A health
check (grpc.health.v1) runs before and after.

Exit status 0 only when the server was SERVING before and after, and every call
was sent, answered OK and checked without a problem; 1 otherwise; 2 for bad usage.

  --target HOST:PORT   the server; loopback only (127.0.0.0/8, ::1, localhost)
  --concurrency C      client threads, 1 to 256
  --requests N         calls in all, 1 to 1000000
  --method M           simulate (default): a shot on each table; plan: a plan for
                       each table, with robot limits varied per call (min speed 0.3
                       to 0.8 m/s, max 3 to 6 m/s, topspin 0.5 to 1, sidespin 0.2 to
                       0.5 of the rolling spin), the default ball on and noise
  --budget-ms MS       plan: each plan's time budget, ms (default 25; 1 to 60000,
                       at most the server's --max-budget-ms)
  --tables DIR         the tables: every *.json in DIR (a TableState each, as for
                       snooker simulate --table), in name order, used in turn;
                       default: 64 built-in tables (0-15 reds, some colours, placed
                       at random; every fourth with two balls overlapping by 0.3 mm
                       when the server repairs that)
  --seed S             seed of the built-in tables and of the shots (default 1)
  --max-seconds S      no call is sent after S seconds (default 600, at most 3600)
  --json               one JSON object: {"target", "method", "concurrency",
                       "requests", "completed", "elapsedS", "throughputPerS", "budgetMs",
                       "plansWithShots" and "plansCutShort" (plan: OK answers with
                       a shot, and those the clock cut short),
                       "latencyMs": {"p50", "p90", "p99", "max", "mean"}, "statuses":
                       {"OK": n, ...}, "errors", "badAnswers", "problems": [...],
                       "ballsMoved", "healthBefore", "healthAfter", "timeBoundHit"}
)";

using Clock = std::chrono::steady_clock;

// What the answers are checked against: the server's own model.
struct Expectations {
  double width = 0, length = 0;
  double vision_tolerance_mm = 0;
  double ball_radius = 0;
};

struct Outcome {
  bool done = false;  // sent and answered
  grpc::StatusCode code = grpc::StatusCode::OK;
  double latency_ms = 0;
  std::string problem;  // empty: the answer checked out (or the call failed)
  int balls_moved = 0;
  int shots = 0;  // plan: shots in the answer
  bool cut_short = false;  // plan: the clock stopped some of its work (PlanResponse.cut_short)
};

std::string Num(double x) { return server::FormatNumber(x); }

// A plan's budget in the load test unless --budget-ms says otherwise, ms: small, so
// that a 2-core server answers 50 plans a second (docs/load.md).
constexpr double kDefaultPlanBudgetMs = 25;

// Checks a Simulate answer against its request; the first problem, or "".
std::string CheckSimulate(const v1::SimulateRequest& request, const v1::SimulateResponse& r,
                          const Expectations& e) {
  const v1::TableState& t = request.table();
  std::set<std::string> ids;
  for (const v1::Ball& b : t.balls()) ids.insert(b.id());
  static const std::set<std::string> kStatuses = {"at rest", "event limit reached",
                                                  "time limit reached"};
  if (kStatuses.count(r.status()) == 0) return "status \"" + r.status() + "\"";
  if (!(std::isfinite(r.duration_s()) && r.duration_s() >= 0)) return "durationS " + Num(r.duration_s());
  if (r.final_balls_size() != t.balls_size()) {
    return std::to_string(r.final_balls_size()) + " final balls for " +
           std::to_string(t.balls_size()) + " balls";
  }
  constexpr double kSlack = 0.2;  // m: a ball may rest in a pocket's jaws
  for (int i = 0; i < t.balls_size(); ++i) {
    const v1::FinalBall& b = r.final_balls(i);
    if (b.id() != t.balls(i).id()) return "final ball " + std::to_string(i) + " is \"" + b.id() + "\"";
    const double x = b.position().x(), y = b.position().y();
    if (!(std::isfinite(x) && std::isfinite(y) && x > -kSlack && x < e.width + kSlack &&
          y > -kSlack && y < e.length + kSlack)) {
      return "ball \"" + b.id() + "\" ended at (" + Num(x) + ", " + Num(y) + ")";
    }
  }
  double last = 0;
  for (const v1::Event& ev : r.events()) {
    if (!(std::isfinite(ev.time()) && ev.time() >= last)) {
      return "event time " + Num(ev.time()) + " after " + Num(last);
    }
    last = ev.time();
    if (ev.balls_size() < 1) return "an event without a ball";
    for (const std::string& id : ev.balls()) {
      if (ids.count(id) == 0) return "an event names ball \"" + id + "\"";
    }
  }
  for (const v1::Warning& w : r.warnings()) {
    if (ids.count(w.ball_id()) == 0) return "a warning names ball \"" + w.ball_id() + "\"";
    if (!(w.moved_mm() >= 0 && w.moved_mm() <= e.vision_tolerance_mm + 1e-9)) {
      return "ball \"" + w.ball_id() + "\" moved " + Num(w.moved_mm()) + " mm, beyond the tolerance";
    }
  }
  return "";
}

// Checks a Plan answer against its request; the first problem, or "".
std::string CheckPlan(const v1::PlanRequest& request, const v1::PlanResponse& r, const Expectations& e) {
  const v1::TableState& t = request.table();
  std::set<std::string> ids;
  for (const v1::Ball& b : t.balls()) ids.insert(b.id());
  if (!r.final()) return "the answer is not marked final";
  if (r.shots_size() > request.max_shots()) {
    return std::to_string(r.shots_size()) + " shots for max_shots " + std::to_string(request.max_shots());
  }
  if (r.shots_size() == 0 && r.reason().empty()) return "no shot and no reason";
  const v1::RobotLimits& l = request.limits();
  constexpr double kRel = 1e-9;
  for (int k = 0; k < r.shots_size(); ++k) {
    const v1::PlannedShot& s = r.shots(k);
    const std::string which = "shot " + std::to_string(k + 1) + ": ";
    if (!(s.speed() >= l.min_speed() * (1 - kRel) && s.speed() <= l.max_speed() * (1 + kRel))) {
      return which + "speed " + Num(s.speed()) + " m/s outside [" + Num(l.min_speed()) + ", " +
             Num(l.max_speed()) + "]";
    }
    const double rolling = s.speed() / e.ball_radius;
    if (!(std::abs(s.topspin()) <= l.max_topspin_fraction() * rolling * (1 + kRel) + 1e-12)) {
      return which + "topspin " + Num(s.topspin()) + " rad/s beyond " + Num(l.max_topspin_fraction()) +
             " of the rolling spin " + Num(rolling);
    }
    if (!(std::abs(s.sidespin()) <= l.max_sidespin_fraction() * rolling * (1 + kRel) + 1e-12)) {
      return which + "sidespin " + Num(s.sidespin()) + " rad/s beyond " +
             Num(l.max_sidespin_fraction()) + " of the rolling spin " + Num(rolling);
    }
    if (!(s.pot_probability() >= 0 && s.pot_probability() <= 1)) {
      return which + "potProbability " + Num(s.pot_probability());
    }
    if (!(s.position_value() >= 0 && s.position_value() <= 1.48 + 1e-9)) {
      return which + "positionValue " + Num(s.position_value());
    }
    if (!(std::isfinite(s.heading_deg()) && std::isfinite(s.cut_deg()) &&
          std::isfinite(s.cue_ball_end().x()) && std::isfinite(s.cue_ball_end().y()))) {
      return which + "a number that is not finite";
    }
    if (ids.count(s.object_ball()) == 0) return which + "object ball \"" + s.object_ball() + "\"";
    if (!s.next_ball().empty() && ids.count(s.next_ball()) == 0) {
      return which + "next ball \"" + s.next_ball() + "\"";
    }
    double last = 0;
    for (const v1::Event& ev : s.events()) {
      if (!(std::isfinite(ev.time()) && ev.time() >= last)) {
        return which + "event time " + Num(ev.time()) + " after " + Num(last);
      }
      last = ev.time();
      for (const std::string& id : ev.balls()) {
        if (ids.count(id) == 0) return which + "an event names ball \"" + id + "\"";
      }
    }
  }
  for (const v1::Warning& w : r.warnings()) {
    if (ids.count(w.ball_id()) == 0) return "a warning names ball \"" + w.ball_id() + "\"";
    if (!(w.moved_mm() >= 0 && w.moved_mm() <= e.vision_tolerance_mm + 1e-9)) {
      return "ball \"" + w.ball_id() + "\" moved " + Num(w.moved_mm()) + " mm, beyond the tolerance";
    }
  }
  return "";
}

// A plan request for a table: the budget, and robot limits varied by `random`.
v1::PlanRequest PlanFor(const v1::TableState& table, double budget_ms, LoadRandom& random) {
  v1::PlanRequest r;
  *r.mutable_table() = table;
  r.set_time_budget_ms(budget_ms);
  r.set_max_shots(3);
  r.set_seed(random.Next() >> 1);
  v1::RobotLimits* l = r.mutable_limits();
  l->set_min_speed(random.Uniform(0.3, 0.8));
  l->set_max_speed(random.Uniform(3.0, 6.0));
  l->set_max_topspin_fraction(random.Uniform(0.5, 1.0));
  l->set_max_sidespin_fraction(random.Uniform(0.2, 0.5));
  return r;
}

double Percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0;
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

constexpr const char* kCommand = "snooker loadtest";

// The flags, checked.
struct Settings {
  ClientOptions client;
  std::string method;
  bool plan = false;  // --method plan
  long concurrency = 0;
  std::size_t requests = 0;
  std::string tables_dir;  // empty: the built-in tables
  std::uint64_t seed = 1;
  long max_seconds = 600;
  double budget_ms = kDefaultPlanBudgetMs;
  bool json = false;
};

// Reads and checks the flags into `s`. An exit code when the command ends here (after
// --help, or a usage error said on `err`); nothing when the load test goes ahead.
std::optional<int> ParseSettings(const std::vector<std::string>& argv, std::ostream& out,
                                 std::ostream& err, Settings* s) {
  std::set<std::string> valued = {"concurrency", "requests", "method", "tables", "seed", "max-seconds",
                                  "budget-ms"};
  for (const std::string& flag : ClientFlags("target")) valued.insert(flag);
  Args args(argv, valued, {"json", "help"});
  if (args.error().empty() && args.Switch("help")) {
    out << kLoadtestHelp << "\n" << ClientFlagsHelp();
    return kExitOk;
  }
  const auto concurrency = args.Integer("concurrency", std::nullopt, 1, 256);
  const auto requests = args.Integer("requests", std::nullopt, 1, 1'000'000);
  const auto method = args.Text("method", "simulate");
  const auto tables_dir = args.Text("tables", "");
  const auto seed = args.Unsigned64("seed", 1);
  const auto max_seconds = args.Integer("max-seconds", 600, 1, 3600);
  const auto budget_ms = args.Number("budget-ms", kDefaultPlanBudgetMs);
  if (!ClientOptionsFrom(args, kCommand, "target", 10'000, &s->client, err)) return kExitUsage;
  if (args.error().empty() && s->client.target.empty()) {
    err << kCommand << ": --target is required\n";
    return kExitUsage;
  }
  if (!args.error().empty()) {
    err << kCommand << ": " << args.error() << "\n(see snooker loadtest --help)\n";
    return kExitUsage;
  }
  if (!server::IsLoopbackAddress(s->client.target)) {
    err << kCommand << ": refusing --target " << s->client.target
        << ": load goes only to this machine (127.0.0.0/8, ::1, localhost)\n";
    return kExitUsage;
  }
  if (*method != "simulate" && *method != "plan") {
    err << kCommand << ": --method '" << *method << "': simulate or plan\n";
    return kExitUsage;
  }
  if (!(*budget_ms >= 1 && *budget_ms <= 60'000)) {
    err << kCommand << ": --budget-ms " << Num(*budget_ms) << " is outside [1, 60000]\n";
    return kExitUsage;
  }
  s->method = *method;
  s->plan = *method == "plan";
  s->concurrency = *concurrency;
  s->requests = static_cast<std::size_t>(*requests);
  s->tables_dir = *tables_dir;
  s->seed = *seed;
  s->max_seconds = *max_seconds;
  s->budget_ms = *budget_ms;
  s->json = args.Switch("json");
  return std::nullopt;
}

// The server's health (SERVING required) and its model, what the answers are checked
// against: kExitOk, or the exit code after saying why on `err`.
int ReadServer(const std::shared_ptr<grpc::Channel>& channel, const ClientOptions& client,
               std::string* health, Expectations* expect, std::ostream& err) {
  if (const grpc::Status st = CheckHealth(channel, "snooker.v1.ShotPlanner", client.deadline, health);
      !st.ok()) {
    err << kCommand << ": health check of " << client.target << " failed: "
        << StatusCodeName(st.error_code()) << ": " << st.error_message() << "\n";
    return kExitFailure;
  }
  if (*health != "SERVING") {
    err << kCommand << ": " << client.target << " reports " << *health
        << " for snooker.v1.ShotPlanner: no load sent\n";
    return kExitFailure;
  }
  v1::GetModelResponse model;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + client.deadline);
  const std::string request_id = NameCall(&context);
  const grpc::Status st = v1::ShotPlanner::NewStub(channel)->GetModel(&context, {}, &model);
  if (!st.ok()) return ReportCallError(kCommand, client.target, st, request_id, err);
  expect->width = model.table().width_m();
  expect->length = model.table().length_m();
  expect->vision_tolerance_mm = model.service().vision_tolerance_mm();
  expect->ball_radius = model.ball().radius_m();
  return kExitOk;
}

// The tables of the calls: the files of --tables, or the built-in ones. False with
// the reason on `err`.
bool ChooseTables(const Settings& s, const Expectations& expect, std::vector<v1::TableState>* tables,
                  std::ostream& err) {
  if (!s.tables_dir.empty()) {
    std::string why;
    if (!ReadTables(s.tables_dir, tables, &why)) {
      err << kCommand << ": --tables: " << why << "\n";
      return false;
    }
    return true;
  }
  // Overlaps of 0.3 mm only for a server that repairs them.
  constexpr double kOverlapMm = 0.3;
  *tables = VariedTables(s.seed, 64,
                         expect.vision_tolerance_mm >= kOverlapMm ? kOverlapMm : 0);
  return true;
}

// Call number `i`: its request (from its table and a generator seeded by the seed and
// `i`), sent, timed and its answer checked.
Outcome CallOnce(v1::ShotPlanner::Stub& stub, const Settings& s, const v1::TableState& table,
                 std::size_t i, const Expectations& expect) {
  LoadRandom random(s.seed * 0x9E3779B97F4A7C15ull + i);
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + s.client.deadline);
  Outcome o;
  grpc::Status st;
  const auto start = Clock::now();
  if (s.plan) {
    const v1::PlanRequest request = PlanFor(table, s.budget_ms, random);
    v1::PlanResponse response;
    st = stub.Plan(&context, request, &response);
    o.latency_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (st.ok()) {
      o.problem = CheckPlan(request, response, expect);
      o.balls_moved = response.warnings_size();
      o.shots = response.shots_size();
      o.cut_short = response.cut_short();
    }
  } else {
    v1::SimulateRequest request;
    *request.mutable_table() = table;
    *request.mutable_shot() = ShotAtABall(request.table(), random);
    v1::SimulateResponse response;
    st = stub.Simulate(&context, request, &response);
    o.latency_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (st.ok()) {
      o.problem = CheckSimulate(request, response, expect);
      o.balls_moved = response.warnings_size();
    }
  }
  o.done = true;
  o.code = st.error_code();
  if (!st.ok()) o.problem = std::string(StatusCodeName(st.error_code())) + ": " + st.error_message();
  return o;
}

// The calls sent: their outcomes, in call order, and how long the sending took.
struct Load {
  std::vector<Outcome> outcomes;  // not done: not sent (the time bound came first)
  double elapsed_s = 0;
  bool time_bound_hit = false;
};

// Sends the calls from --concurrency threads, each with a connection of its own, until
// all are sent or --max-seconds have passed. When the system will not start all the
// threads, `error` says which and the load sent is no measure.
Load SendLoad(const Settings& s, const std::vector<v1::TableState>& tables, const Expectations& expect,
              std::string* error) {
  Load load;
  load.outcomes.resize(s.requests);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> time_bound_hit{false};
  const auto t0 = Clock::now();
  const auto stop_sending = t0 + std::chrono::seconds(s.max_seconds);
  auto worker = [&] {
    auto stub = v1::ShotPlanner::NewStub(MakeChannel(s.client, /*own_connection=*/true));
    for (;;) {  // at most s.requests turns among all workers: `next` only grows
      const std::size_t i = next.fetch_add(1);
      if (i >= s.requests) return;
      if (Clock::now() >= stop_sending) {
        time_bound_hit = true;
        return;
      }
      load.outcomes[i] = CallOnce(*stub, s, tables[i % tables.size()], i, expect);
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(static_cast<std::size_t>(s.concurrency));
  for (long c = 0; c < s.concurrency; ++c) {
    try {
      threads.emplace_back(worker);
    } catch (const std::system_error& e) {
      // Fewer clients than asked would measure another load: the ones started stop
      // after their call in flight, and the run fails, naming the thread.
      next = s.requests;
      for (std::thread& t : threads) t.join();
      *error = "could not start client thread " + std::to_string(c + 1) + " of " +
               std::to_string(s.concurrency) + " (" + e.what() + "); lower --concurrency or raise the limit";
      return load;
    }
  }
  for (std::thread& t : threads) t.join();
  load.elapsed_s = std::chrono::duration<double>(Clock::now() - t0).count();
  load.time_bound_hit = time_bound_hit.load();
  return load;
}

// The outcomes summed up for the report.
struct Summary {
  std::size_t completed = 0, errors = 0, bad = 0, moved = 0, with_shots = 0, cut_short = 0;
  std::map<std::string, std::size_t> statuses;  // by status code name
  std::vector<double> latencies;                // ms, sorted
  std::vector<std::string> problems;            // the first five
  double mean = 0;                              // ms
  double throughput = 0;                        // calls/s
};

Summary Summarize(const Load& load) {
  Summary sum;
  for (std::size_t i = 0; i < load.outcomes.size(); ++i) {
    const Outcome& o = load.outcomes[i];
    if (!o.done) continue;  // not sent: the time bound came first
    ++sum.completed;
    sum.latencies.push_back(o.latency_ms);
    ++sum.statuses[StatusCodeName(o.code)];
    sum.moved += static_cast<std::size_t>(o.balls_moved);
    if (o.code == grpc::StatusCode::OK && o.shots > 0) ++sum.with_shots;
    if (o.code == grpc::StatusCode::OK && o.cut_short) ++sum.cut_short;
    if (o.code != grpc::StatusCode::OK) ++sum.errors;
    else if (!o.problem.empty()) ++sum.bad;
    if (!o.problem.empty() && sum.problems.size() < 5) {
      sum.problems.push_back("call " + std::to_string(i) + ": " +
                             server::BoundMessage(o.problem).substr(0, 300));
    }
  }
  std::sort(sum.latencies.begin(), sum.latencies.end());
  for (double l : sum.latencies) sum.mean += l;
  sum.mean = sum.latencies.empty() ? 0 : sum.mean / static_cast<double>(sum.latencies.size());
  sum.throughput = load.elapsed_s > 0 ? static_cast<double>(sum.completed) / load.elapsed_s : 0;
  return sum;
}

// The server's health before and after the load.
struct Health {
  std::string before = "unreachable", after = "unreachable";
};

void PrintJsonReport(const Settings& s, std::size_t table_count, const Load& load, const Summary& sum,
                     const Health& health, std::ostream& out) {
  google::protobuf::Struct j;
  auto& f = *j.mutable_fields();
  f["target"].set_string_value(s.client.target);
  f["method"].set_string_value(s.method);
  f["concurrency"].set_number_value(static_cast<double>(s.concurrency));
  f["requests"].set_number_value(static_cast<double>(s.requests));
  f["completed"].set_number_value(static_cast<double>(sum.completed));
  f["tables"].set_number_value(static_cast<double>(table_count));
  f["elapsedS"].set_number_value(load.elapsed_s);
  f["throughputPerS"].set_number_value(sum.throughput);
  auto& lat = *f["latencyMs"].mutable_struct_value()->mutable_fields();
  lat["p50"].set_number_value(Percentile(sum.latencies, 0.50));
  lat["p90"].set_number_value(Percentile(sum.latencies, 0.90));
  lat["p99"].set_number_value(Percentile(sum.latencies, 0.99));
  lat["max"].set_number_value(sum.latencies.empty() ? 0 : sum.latencies.back());
  lat["mean"].set_number_value(sum.mean);
  auto& st = *f["statuses"].mutable_struct_value()->mutable_fields();
  for (const auto& [name, count] : sum.statuses) st[name].set_number_value(static_cast<double>(count));
  f["errors"].set_number_value(static_cast<double>(sum.errors));
  f["badAnswers"].set_number_value(static_cast<double>(sum.bad));
  auto* list = f["problems"].mutable_list_value();
  for (const std::string& p : sum.problems) list->add_values()->set_string_value(p);
  f["ballsMoved"].set_number_value(static_cast<double>(sum.moved));
  if (s.plan) {
    f["budgetMs"].set_number_value(s.budget_ms);
    f["plansWithShots"].set_number_value(static_cast<double>(sum.with_shots));
    f["plansCutShort"].set_number_value(static_cast<double>(sum.cut_short));
  }
  f["healthBefore"].set_string_value(health.before);
  f["healthAfter"].set_string_value(health.after);
  f["timeBoundHit"].set_bool_value(load.time_bound_hit);
  std::string text;
  google::protobuf::util::JsonPrintOptions o;
  (void)google::protobuf::util::MessageToJsonString(j, &text, o);
  out << text << "\n";
}

void PrintReadableReport(const Settings& s, std::size_t table_count, const Load& load,
                         const Summary& sum, const Health& health, std::ostream& out) {
  const std::vector<double>& lat = sum.latencies;
  out << std::fixed << std::setprecision(1) << kCommand << ": " << s.requests << " " << s.method
      << " calls to " << s.client.target << ", concurrency " << s.concurrency << ", " << table_count
      << (s.tables_dir.empty() ? " built-in tables (seed " + std::to_string(s.seed) + ")"
                               : " tables from " + s.tables_dir)
      << "\n  health: " << health.before << " before, " << health.after << " after\n"
      << "  completed " << sum.completed << " of " << s.requests << " in " << std::setprecision(2)
      << load.elapsed_s << " s: " << std::setprecision(1) << sum.throughput << " calls/s"
      << (load.time_bound_hit ? " (stopped at --max-seconds)" : "") << "\n"
      << "  latency ms: p50 " << std::setprecision(2) << Percentile(lat, 0.5) << ", p90 "
      << Percentile(lat, 0.9) << ", p99 " << Percentile(lat, 0.99) << ", max "
      << (lat.empty() ? 0.0 : lat.back()) << " (mean " << sum.mean << ")\n  statuses:";
  for (const auto& [name, count] : sum.statuses) out << " " << name << " " << count;
  out << "\n  answers with problems: " << sum.bad << "; balls moved by the vision repair: " << sum.moved
      << "\n";
  if (s.plan) {
    out << "  plans: budget " << Num(s.budget_ms) << " ms each; " << sum.with_shots
        << " answers with at least one shot, " << sum.cut_short << " cut short by the clock\n";
  }
  for (const std::string& p : sum.problems) out << "  problem: " << p << "\n";
}

}  // namespace

int RunLoadTest(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Settings s;
  if (const std::optional<int> stop = ParseSettings(argv, out, err, &s)) return *stop;
  // The server's model first: what its answers are checked against. Its health too.
  auto channel = MakeChannel(s.client);
  Health health;
  Expectations expect;
  if (const int rc = ReadServer(channel, s.client, &health.before, &expect, err); rc != kExitOk) return rc;
  std::vector<v1::TableState> tables;
  if (!ChooseTables(s, expect, &tables, err)) return kExitUsage;
  std::string error;
  const Load load = SendLoad(s, tables, expect, &error);
  if (!error.empty()) {
    err << kCommand << ": " << error << "\n";
    return kExitFailure;
  }
  CheckHealth(channel, "snooker.v1.ShotPlanner", s.client.deadline, &health.after);
  const Summary sum = Summarize(load);
  if (s.json) {
    PrintJsonReport(s, tables.size(), load, sum, health, out);
  } else {
    PrintReadableReport(s, tables.size(), load, sum, health, out);
  }
  const bool clean =
      sum.completed == s.requests && sum.errors == 0 && sum.bad == 0 && health.after == "SERVING";
  return clean ? kExitOk : kExitFailure;
}

}  // namespace snooker::cli
