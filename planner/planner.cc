#include "planner/planner.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "physics/core/limits.h"
#include "planner/random.h"
#include "planner/robustness.h"

namespace snooker::planner {
namespace {

using Clock = std::chrono::steady_clock;
using physics::Vec2;

// Monte Carlo samples come in blocks with their own random streams.
constexpr int kBlock = 8;

// Runs fn(task, worker) for tasks [0, tasks) on `threads` workers (the caller's
// thread is worker 0). Tasks are handed out in order; results must not depend on
// which worker runs a task. An exception in a worker is rethrown here.
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
  for (int w = 1; w <= extra; ++w) pool.emplace_back(work, w);
  work(0);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

std::string Num(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

void Check(std::ostringstream& out, bool ok, const std::string& field, double value,
           const std::string& rule) {
  if (ok) return;
  if (out.tellp() > 0) out << "; ";
  out << field << " = " << Num(value) << " (" << rule << ")";
}

bool In(double x, double lo, double hi) { return std::isfinite(x) && x >= lo && x <= hi; }

// One worker's simulators, reused across its tasks.
struct Worker {
  Worker(const physics::TableModel& table, const Planner::Config& c)
      : search(table, c.search), full(table, c.full) {}
  ShotSimulator search;
  ShotSimulator full;
  std::int64_t evaluations = 0;
};

}  // namespace

const char* ToString(PlanStatus s) {
  switch (s) {
    case PlanStatus::kOk: return "ok";
    case PlanStatus::kNoPot: return "no pot";
    case PlanStatus::kInvalidRequest: return "invalid request";
    case PlanStatus::kDeadline: return "deadline";
    case PlanStatus::kCancelled: return "cancelled";
  }
  return "unknown";
}

Planner::Planner(const Config& config) : config_(config) {
  if (config_.table == &physics::DefaultTable()) {
    pockets_ = &PocketModel::Default();
    throws_ = &ThrowModel::Default();
  } else {
    own_pockets_ = std::make_unique<PocketModel>(*config_.table, config_.full, PocketModel::Options{});
    own_throws_ = std::make_unique<ThrowModel>(config_.full, ThrowModel::Options{});
    pockets_ = own_pockets_.get();
    throws_ = own_throws_.get();
  }
}

const Planner& Planner::Default() {
  static const Planner planner;
  return planner;
}

PotContext Planner::ContextFor(const PlanRequest& request) const {
  PotContext ctx;
  ctx.table = config_.table;
  ctx.pockets = pockets_;
  ctx.throws = throws_;
  ctx.noise = request.noise;
  ctx.position_sigma = request.position_sigma;
  ctx.cue = request.limits.cue;
  return ctx;
}

std::string Planner::Validate(const PlanRequest& r) const {
  std::ostringstream out;
  const TableState& t = r.table;
  const int n = static_cast<int>(t.balls.size());
  Check(out, n <= physics::limits::kMaxBalls, "table.balls", n,
        "at most " + std::to_string(physics::limits::kMaxBalls) + " balls");
  Check(out, t.Count(BallKind::kCue) == 1, "table.balls", t.Count(BallKind::kCue),
        "cue balls: exactly one");
  Check(out, t.reds() <= physics::kRedCount, "table.balls", t.reds(), "reds: at most 15");
  for (int c = 0; c < physics::kColourCount; ++c) {
    const BallKind k = KindOf(static_cast<physics::Colour>(c));
    Check(out, t.Count(k) <= 1, "table.balls", t.Count(k),
          std::string(ToString(k)) + " balls: at most one");
  }
  bool finite = true;
  for (int i = 0; i < n; ++i) {
    const Vec2& p = t.balls[static_cast<size_t>(i)].position;
    if (!p.allFinite()) {
      finite = false;
      Check(out, false, "table.balls[" + std::to_string(i) + "].position", p.x() + p.y(),
            "must be finite, m");
    }
  }
  if (finite && n > 0 && n <= physics::limits::kMaxBalls) {
    std::vector<physics::BallPlacement> placed;
    std::vector<std::string> names;
    names.reserve(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      names.push_back(std::string(ToString(t.balls[static_cast<size_t>(i)].kind)) + " (ball " +
                      std::to_string(i) + ")");
    }
    for (int i = 0; i < n; ++i) placed.push_back({names[static_cast<size_t>(i)], t.balls[static_cast<size_t>(i)].position});
    const std::string msg = config_.table->ValidatePlacement(placed);
    if (!msg.empty()) {
      if (out.tellp() > 0) out << "; ";
      out << "table.balls: " << msg;
    }
  }
  if (r.ball_on) {
    bool present = false;
    for (const Ball& b : t.balls) present = present || IsLegalTarget(*r.ball_on, b.kind);
    if (!present) {
      if (out.tellp() > 0) out << "; ";
      out << "ball_on = " << ToString(*r.ball_on) << " (no such ball on the table)";
    }
  }
  const RobotLimits& l = r.limits;
  const physics::Range speed = physics::limits::kShotSpeed;
  Check(out, In(l.min_speed, 0, speed.hi), "limits.min_speed", l.min_speed,
        "in [0, " + Num(speed.hi) + "] m/s");
  Check(out, In(l.max_speed, 0.05, speed.hi) && l.max_speed > l.min_speed, "limits.max_speed",
        l.max_speed, "in [0.05, " + Num(speed.hi) + "] m/s and above limits.min_speed");
  Check(out, In(l.max_topspin_fraction, 0, 3), "limits.max_topspin_fraction",
        l.max_topspin_fraction, "in [0, 3] of the rolling spin");
  Check(out, In(l.max_sidespin_fraction, 0, 3), "limits.max_sidespin_fraction",
        l.max_sidespin_fraction, "in [0, 3] of the rolling spin");
  Check(out, In(l.cue.length, 0, 2), "limits.cue.length", l.cue.length, "in [0, 2] m");
  Check(out, In(l.cue.radius, 0, 0.05), "limits.cue.radius", l.cue.radius, "in [0, 0.05] m");
  const NoiseModel& z = r.noise;
  Check(out, In(z.heading, 0, physics::DegToRad(10)), "noise.heading", z.heading,
        "in [0, 10 deg] rad");
  Check(out, In(z.speed_fraction, 0, 0.5), "noise.speed_fraction", z.speed_fraction, "in [0, 0.5]");
  Check(out, In(z.topspin, 0, 100), "noise.topspin", z.topspin, "in [0, 100] rad/s");
  Check(out, In(z.sidespin, 0, 100), "noise.sidespin", z.sidespin, "in [0, 100] rad/s");
  Check(out, In(z.position, 0, 0.05), "noise.position", z.position, "in [0, 0.05] m");
  Check(out, r.position_sigma.empty() || static_cast<int>(r.position_sigma.size()) == n,
        "position_sigma", static_cast<double>(r.position_sigma.size()),
        "entries: none or one per ball");
  for (size_t i = 0; i < r.position_sigma.size(); ++i) {
    Check(out, In(r.position_sigma[i], 0, 0.05), "position_sigma[" + std::to_string(i) + "]",
          r.position_sigma[i], "in [0, 0.05] m");
  }
  Check(out, In(r.time_budget, 1e-3, 60), "time_budget", r.time_budget, "in [0.001, 60] s");
  Check(out, r.max_shots >= 1 && r.max_shots <= 20, "max_shots", r.max_shots, "in [1, 20]");
  Check(out, r.threads >= 1 && r.threads <= 64, "threads", r.threads, "in [1, 64]");
  Check(out, r.max_simulations >= 0 && r.max_simulations <= 100'000'000, "max_simulations",
        static_cast<double>(r.max_simulations), "in [0, 1e8]");
  Check(out, r.monte_carlo_samples >= 0 && r.monte_carlo_samples <= 100'000,
        "monte_carlo_samples", r.monte_carlo_samples, "in [0, 100000]");
  return out.str();
}

PlanAnswer Planner::Plan(const PlanRequest& request) const {
  const Clock::time_point start = Clock::now();
  PlanAnswer answer;
  auto finish = [&]() -> PlanAnswer {
    answer.elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    return std::move(answer);
  };
  if (std::string msg = Validate(request); !msg.empty()) {
    answer.status = PlanStatus::kInvalidRequest;
    answer.reason = std::move(msg);
    return finish();
  }
  const TableState& table = request.table;
  const int cue = table.cue_index();
  const auto on = request.ball_on ? request.ball_on : OpeningBallOn(table);
  answer.ball_on = on;
  if (!on) {
    answer.status = PlanStatus::kNoPot;
    answer.reason = "no ball on: the table holds only the cue ball";
    return finish();
  }
  const PotContext ctx = ContextFor(request);
  SearchSettings settings = config_.search_settings;
  settings.limits = request.limits;
  settings.position_play = request.position_play;

  // Deadlines of the phases and the work they may do.
  const auto budget = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(request.time_budget));
  // The work ends a little before the budget: the last simulation in flight, the
  // threads' join and the answer's assembly come after it.
  const Clock::time_point end =
      std::min(start + std::chrono::duration_cast<Clock::duration>(budget * config_.end_share),
               request.deadline);
  auto at = [&](double share) {
    return std::min(end, start + std::chrono::duration_cast<Clock::duration>(budget * share));
  };
  const StopControl search_stop{at(config_.search_share), request.cancel};
  const StopControl mc_stop{at(config_.search_share + config_.monte_carlo_share), request.cancel};
  const StopControl final_stop{end, request.cancel};
  const double total_sims =
      request.max_simulations > 0
          ? static_cast<double>(request.max_simulations)
          : config_.simulations_per_ms * request.time_budget * 1e3 * request.threads;
  const double search_sims = total_sims * config_.search_share;
  const double mc_sims = total_sims * config_.monte_carlo_share;

  // 1. Candidates.
  const CandidateSet set = EnumerateCandidates(table, *on, ctx);
  answer.candidate_pairs = set.pairs;
  answer.candidates = static_cast<int>(set.candidates.size());
  if (set.candidates.empty()) {
    answer.status = PlanStatus::kNoPot;
    std::ostringstream why;
    why << "no pot: none of the " << set.pairs << " ball-pocket pairs for the ball on ("
        << ToString(*on) << ") survives pruning";
    for (int k = 1; k < kPruneReasonCount; ++k) {
      if (set.pruned[static_cast<size_t>(k)] > 0) {
        why << "; " << ToString(static_cast<PruneReason>(k)) << ": " << set.pruned[static_cast<size_t>(k)];
      }
    }
    answer.reason = why.str();
    return finish();
  }

  // 2. How much search each candidate gets: by its prior, the estimated points
  // p (value + continuation), the most promising most; hopeless ones (under a tenth
  // of the best prior) none.
  const double continuation = settings.position.continuation;
  auto prior = [&](const Candidate& c) {
    return c.estimate.probability *
           (Value(table.balls[static_cast<size_t>(c.object)].kind) + continuation);
  };
  std::vector<const Candidate*> ordered;
  for (const Candidate& c : set.candidates) ordered.push_back(&c);
  std::stable_sort(ordered.begin(), ordered.end(),
                   [&](const Candidate* a, const Candidate* b) { return prior(*a) > prior(*b); });
  std::vector<const Candidate*> chosen;
  std::vector<double> weight;
  const double best_prior = prior(*ordered.front());
  for (const Candidate* c : ordered) {
    if (static_cast<int>(chosen.size()) >= config_.max_candidates) break;
    if (!chosen.empty() && prior(*c) < 0.1 * best_prior) break;
    chosen.push_back(c);
    const size_t rank = chosen.size() - 1;
    weight.push_back(rank < 4 ? 1.0 : rank < 8 ? 0.5 : 0.25);
  }
  std::vector<int> evals;
  for (;;) {
    double sum = 0;
    for (double w : weight) sum += w;
    evals.assign(chosen.size(), 0);
    bool enough = true;
    for (size_t i = 0; i < chosen.size(); ++i) {
      evals[i] = static_cast<int>(search_sims * weight[i] / sum);
      enough = enough && evals[i] >= config_.min_evaluations;
    }
    if (enough || chosen.size() == 1) break;
    chosen.pop_back();
    weight.pop_back();
  }
  for (int& e : evals) e = std::max(e, config_.min_evaluations);
  answer.searched = static_cast<int>(chosen.size());

  // 3. Search and verify, candidates across the workers.
  const int threads = request.threads;
  std::vector<std::unique_ptr<Worker>> workers;
  for (int w = 0; w < std::min(threads, static_cast<int>(chosen.size())); ++w) {
    workers.push_back(std::make_unique<Worker>(*config_.table, config_));
  }
  std::vector<std::optional<PlannedShot>> found(chosen.size());
  std::vector<int> failed_verification(chosen.size(), 0);
  std::vector<int> search_sims_done(chosen.size(), 0);
  std::vector<bool> interrupted(chosen.size(), false);
  std::mutex progress_mutex;
  double best_reported = -std::numeric_limits<double>::infinity();
  PotContext after_ctx = ctx;
  after_ctx.position_sigma.clear();

  auto task_of = [&](const Candidate& cand) {
    return static_cast<size_t>(std::find(chosen.begin(), chosen.end(), &cand) - chosen.begin());
  };
  auto verify = [&](Worker& w, const Candidate& cand, const ShotCandidate& sc) -> std::optional<PlannedShot> {
    const ShotSetup setup{&table, cue, cand.object, cand.pocket, *on};
    const ShotOutcome& out = w.full.Run(setup, sc.shot, {}, ShotSimulator::Mode::kFull, final_stop.AsInterrupt());
    if (!out.success) {
      // An interrupted check says nothing about the shot: it is dropped unverified.
      if (out.status != physics::SimStatus::kInterrupted) failed_verification[task_of(cand)] = 1;
      return std::nullopt;
    }
    PlannedShot ps;
    ps.shot = sc.shot;
    ps.cut = sc.cut;
    ps.object_ball = cand.object;
    ps.pocket = cand.pocket;
    ps.pot_probability = sc.pot_estimate;
    ps.pot_estimate = sc.pot_estimate;
    const auto events = w.full.simulator().events();
    ps.events.assign(events.begin(), events.end());
    std::vector<Vec2> finals;
    for (const physics::BallState& b : w.full.final_balls()) finals.push_back(b.r);
    ps.cue_ball_end = finals[static_cast<size_t>(cue)];
    std::vector<int> origin;
    const TableState after = ApplyShot(table, *on, finals, out.potted, false, *config_.table, &origin);
    const auto next_on = NextBallOn(*on, table.balls[static_cast<size_t>(cand.object)].kind, after);
    PositionValue pos;
    if (next_on) pos = EvaluatePosition(after, *next_on, after_ctx, settings.position);
    ps.position_value = pos.value;
    if (pos.next_ball >= 0) ps.next_ball = origin[static_cast<size_t>(pos.next_ball)];
    const int value = Value(table.balls[static_cast<size_t>(cand.object)].kind);
    ps.search_score = ShotScore(sc.pot_estimate, value, pos, settings.position_play);
    ps.score = ps.search_score;
    return ps;
  };

  ParallelFor(threads, static_cast<int>(chosen.size()), [&](int task, int worker) {
    Worker& w = *workers[static_cast<size_t>(worker)];
    const Candidate& cand = *chosen[static_cast<size_t>(task)];
    SearchSettings s = settings;
    const int e = evals[static_cast<size_t>(task)];
    s.global_evaluations = static_cast<int>(std::lround(e * config_.global_share));
    s.local_evaluations = e - s.global_evaluations;
    const SearchResult r = SearchCandidate(table, *on, cand, ctx, s, w.search, search_stop);
    w.evaluations += r.evaluations;
    search_sims_done[static_cast<size_t>(task)] = r.simulations;
    interrupted[static_cast<size_t>(task)] = r.status == SearchStatus::kInterrupted;
    if (!r.best || final_stop.Due()) return;
    auto ps = verify(w, cand, *r.best);
    if (!ps) return;
    found[static_cast<size_t>(task)] = ps;
    if (request.progress != nullptr) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      if (ps->score > best_reported) {
        best_reported = ps->score;
        request.progress(*ps, request.progress_context);
      }
    }
  });

  std::vector<PlannedShot> shots;
  for (size_t i = 0; i < chosen.size(); ++i) {
    answer.simulations += search_sims_done[i] + (found[i] || failed_verification[i] ? 1 : 0);
    answer.verification_failures += failed_verification[i];
    answer.deadline_hit = answer.deadline_hit || interrupted[i];
    if (found[i]) shots.push_back(*found[i]);
  }
  for (const auto& w : workers) answer.evaluations += w->evaluations;
  answer.verified = static_cast<int>(shots.size());
  // Search order: by the nominal objective (stable: ties keep candidate order).
  std::stable_sort(shots.begin(), shots.end(), [](const PlannedShot& a, const PlannedShot& b) {
    return a.search_score > b.search_score;
  });

  // 4. Monte Carlo of the best few, blocks across the workers.
  const int ranked = std::min(static_cast<int>(shots.size()),
                              std::max(request.max_shots + 2, config_.min_ranked));
  int blocks = (request.monte_carlo_samples + kBlock - 1) / kBlock;
  if (ranked > 0) blocks = std::min(blocks, static_cast<int>(mc_sims / (ranked * kBlock)));
  blocks = std::max(blocks, request.monte_carlo_samples > 0 ? 1 : 0);
  if (ranked > 0 && blocks > 0 && !mc_stop.Due()) {
    while (static_cast<int>(workers.size()) < std::min(threads, ranked * blocks)) {
      workers.push_back(std::make_unique<Worker>(*config_.table, config_));
    }
    std::vector<MonteCarloTally> tallies(static_cast<size_t>(ranked * blocks));
    ParallelFor(threads, ranked * blocks, [&](int task, int worker) {
      const int s = task / blocks, b = task % blocks;
      const PlannedShot& ps = shots[static_cast<size_t>(s)];
      // Streams keyed by the shot itself (object, pocket) and the block, so a
      // shot's samples do not depend on the other shots ranked with it.
      const std::uint64_t seed =
          DeriveSeed(request.seed, static_cast<std::uint64_t>(ps.object_ball) * 8 +
                                       static_cast<std::uint64_t>(ps.pocket), static_cast<std::uint64_t>(b));
      tallies[static_cast<size_t>(task)] =
          RunSamples(table, *on, ps.object_ball, ps.pocket, ps.shot, ctx, settings,
                     workers[static_cast<size_t>(worker)]->full, mc_stop, seed, kBlock);
    });
    for (int s = 0; s < ranked; ++s) {
      MonteCarloTally t;
      for (int b = 0; b < blocks; ++b) t.Add(tallies[static_cast<size_t>(s * blocks + b)]);
      answer.simulations += t.samples;
      answer.deadline_hit = answer.deadline_hit || t.interrupted;
      PlannedShot& ps = shots[static_cast<size_t>(s)];
      if (t.samples > 0) {
        ps.monte_carlo_samples = t.samples;
        ps.pot_probability = t.success_rate();
        ps.score = t.mean_score();
      }
    }
    // Final ranking: the Monte Carlo mean objective (shots without samples keep
    // their nominal score, already below any sampled competitor in practice).
    std::stable_sort(shots.begin(), shots.begin() + ranked,
                     [](const PlannedShot& a, const PlannedShot& b) { return a.score > b.score; });
  }
  if (static_cast<int>(shots.size()) > request.max_shots) shots.resize(static_cast<size_t>(request.max_shots));
  answer.shots = std::move(shots);

  const bool cancelled = request.cancel != nullptr && request.cancel->load();
  if (!answer.shots.empty()) {
    answer.status = cancelled ? PlanStatus::kCancelled : PlanStatus::kOk;
    if (cancelled) answer.reason = "cancelled: the best shots found so far";
  } else if (cancelled) {
    answer.status = PlanStatus::kCancelled;
    answer.reason = "cancelled before any shot was verified";
  } else if (answer.deadline_hit && answer.verified == 0) {
    answer.status = PlanStatus::kDeadline;
    answer.reason = "the time budget ran out before any shot was verified (" +
                    std::to_string(answer.searched) + " candidates started)";
  } else {
    answer.status = PlanStatus::kNoPot;
    answer.reason = "no pot found: the search of " + std::to_string(answer.searched) + " of " +
                    std::to_string(answer.candidates) +
                    " candidate pots found no shot that pots the ball without a foul";
    if (answer.verification_failures > 0) {
      answer.reason += " (" + std::to_string(answer.verification_failures) +
                       " failed the full-fidelity check)";
    }
  }
  return finish();
}

}  // namespace snooker::planner
