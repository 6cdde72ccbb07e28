#include "planner/planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>

#include "planner/parallel.h"
#include "planner/random.h"
#include "planner/robustness.h"
#include "planner/validate.h"

namespace snooker::planner {
namespace {

using Clock = std::chrono::steady_clock;
using physics::Vec2;

// Monte Carlo samples come in blocks with their own random streams.
constexpr int kBlock = 8;

// One worker's simulators, reused across its tasks.
struct Worker {
  Worker(const physics::TableModel& table, const Planner::Config& c)
      : search(table, c.search), full(table, c.full) {}
  ShotSimulator search;
  ShotSimulator full;
  std::int64_t evaluations = 0;
};

// When each stage of a plan must end, and the simulations it may run.
struct Schedule {
  StopControl search;
  StopControl monte_carlo;
  StopControl final;
  double search_simulations = 0;
  double monte_carlo_simulations = 0;
  // The caller's deadline, not the budget, is what ends the work.
  bool deadline_binds = false;
};

Schedule MakeSchedule(const PlannerConfig& config, const PlanRequest& request, Clock::time_point start) {
  const auto budget = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(request.time_budget));
  // The work ends a little before the budget: the last simulation in flight, the
  // threads' join and the answer's assembly come after it.
  const Clock::time_point budget_end =
      start + std::chrono::duration_cast<Clock::duration>(budget * config.end_share);
  const Clock::time_point end = std::min(budget_end, request.deadline);
  auto at = [&](double share) {
    return std::min(end, start + std::chrono::duration_cast<Clock::duration>(budget * share));
  };
  Schedule s;
  s.search = {at(config.search_share), request.cancel};
  s.monte_carlo = {at(config.search_share + config.monte_carlo_share), request.cancel};
  s.final = {end, request.cancel};
  s.deadline_binds = request.deadline < budget_end;
  const double total = request.max_simulations > 0
                           ? static_cast<double>(request.max_simulations)
                           : config.simulations_per_ms * request.time_budget * 1e3 * request.threads;
  s.search_simulations = total * config.search_share;
  s.monte_carlo_simulations = total * config.monte_carlo_share;
  return s;
}

// One plan from request to answer, as its stages: Prepare (validation, the ball on,
// the candidates), Allocate (which candidates get how much search), SearchAndVerify,
// RankByMonteCarlo, Conclude.
class PlanRun {
 public:
  PlanRun(const Planner& planner, const PlanRequest& request)
      : planner_(planner), config_(planner.config()), request_(request), table_(request.table),
        start_(Clock::now()) {}

  PlanAnswer Run() {
    if (Prepare()) {
      Allocate();
      SearchAndVerify();
      RankByMonteCarlo();
      Conclude();
    }
    answer_.elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    return std::move(answer_);
  }

 private:
  bool Prepare();
  void Allocate();
  void SearchAndVerify();
  std::optional<PlannedShot> Verify(Worker& w, const Candidate& cand, const ShotCandidate& sc, size_t task);
  void RankByMonteCarlo();
  void Conclude();
  void AddWorkers(int count) {
    while (static_cast<int>(workers_.size()) < count) {
      workers_.push_back(std::make_unique<Worker>(*config_.table, config_));
    }
  }

  const Planner& planner_;
  const PlannerConfig& config_;
  const PlanRequest& request_;
  const TableState& table_;
  const Clock::time_point start_;
  PlanAnswer answer_;

  // Prepare.
  BallOn on_ = BallOn::kRed;
  int cue_ = -1;
  PotContext ctx_;
  PotContext after_ctx_;  // the next shot's: vision sees the moved balls afresh
  SearchSettings settings_;
  Schedule schedule_;
  CandidateSet set_;
  // Allocate: the candidates searched, in order of their prior, and their evaluations.
  std::vector<const Candidate*> chosen_;
  std::vector<int> evaluations_;
  // SearchAndVerify, one slot per chosen candidate.
  std::vector<std::unique_ptr<Worker>> workers_;
  std::vector<std::optional<PlannedShot>> found_;
  std::vector<int> failed_verification_;
  // Verified shots, best first.
  std::vector<PlannedShot> shots_;
};

bool PlanRun::Prepare() {
  if (std::vector<FieldError> errors = ValidatePlanRequest(request_, *config_.table); !errors.empty()) {
    answer_.status = PlanStatus::kInvalidRequest;
    answer_.reason = Describe(errors);
    return false;
  }
  cue_ = table_.cue_index();
  const auto on = request_.ball_on ? request_.ball_on : OpeningBallOn(table_);
  answer_.ball_on = on;
  if (!on) {
    answer_.status = PlanStatus::kNoPot;
    answer_.reason = "no ball on: the table holds only the cue ball";
    return false;
  }
  on_ = *on;
  ctx_ = planner_.ContextFor(request_);
  after_ctx_ = ctx_;
  after_ctx_.position_sigma.clear();
  settings_ = config_.search_settings;
  settings_.limits = request_.limits;
  settings_.position_play = request_.position_play;
  schedule_ = MakeSchedule(config_, request_, start_);
  set_ = EnumerateCandidates(table_, on_, ctx_);
  answer_.candidate_pairs = set_.pairs;
  answer_.candidates = static_cast<int>(set_.candidates.size());
  if (set_.candidates.empty()) {
    answer_.status = PlanStatus::kNoPot;
    std::ostringstream why;
    why << "no pot: none of the " << set_.pairs << " ball-pocket pairs for the ball on ("
        << ToString(on_) << ") survives pruning";
    for (int k = 1; k < kPruneReasonCount; ++k) {
      if (set_.pruned[static_cast<size_t>(k)] > 0) {
        why << "; " << ToString(static_cast<PruneReason>(k)) << ": " << set_.pruned[static_cast<size_t>(k)];
      }
    }
    answer_.reason = why.str();
    return false;
  }
  return true;
}

// How much search each candidate gets: by its prior, the estimated points p (value
// + continuation), the most promising most; hopeless ones none.
void PlanRun::Allocate() {
  const double continuation = settings_.position.continuation;
  auto prior = [&](const Candidate& c) {
    return c.estimate.probability * (Value(table_.balls[static_cast<size_t>(c.object)].kind) + continuation);
  };
  std::vector<const Candidate*> ordered;
  for (const Candidate& c : set_.candidates) ordered.push_back(&c);
  std::stable_sort(ordered.begin(), ordered.end(),
                   [&](const Candidate* a, const Candidate* b) { return prior(*a) > prior(*b); });
  std::vector<double> weight;
  const double best_prior = prior(*ordered.front());
  for (const Candidate* c : ordered) {
    if (static_cast<int>(chosen_.size()) >= config_.max_candidates) break;
    if (!chosen_.empty() && prior(*c) < config_.min_prior_share * best_prior) break;
    chosen_.push_back(c);
    weight.push_back(config_.SearchWeight(static_cast<int>(chosen_.size()) - 1));
  }
  // Drop the least promising until every candidate gets a worthwhile search.
  for (;;) {
    double sum = 0;
    for (double w : weight) sum += w;
    evaluations_.assign(chosen_.size(), 0);
    bool enough = true;
    for (size_t i = 0; i < chosen_.size(); ++i) {
      evaluations_[i] = static_cast<int>(schedule_.search_simulations * weight[i] / sum);
      enough = enough && evaluations_[i] >= config_.min_evaluations;
    }
    if (enough || chosen_.size() == 1) break;
    chosen_.pop_back();
    weight.pop_back();
  }
  for (int& e : evaluations_) e = std::max(e, config_.min_evaluations);
  answer_.searched = static_cast<int>(chosen_.size());
}

// The candidate's best shot simulated again at full fidelity, to the end. Its label
// (object ball and pocket) is what this simulation did, not what was intended.
std::optional<PlannedShot> PlanRun::Verify(Worker& w, const Candidate& cand, const ShotCandidate& sc,
                                           size_t task) {
  const ShotSetup setup{&table_, cue_, cand.object, cand.pocket, on_};
  const ShotOutcome& out =
      w.full.Run(setup, sc.shot, {}, ShotSimulator::Mode::kFull, schedule_.final.AsInterrupt());
  if (!out.success) {
    // An interrupted check says nothing about the shot: it is dropped unverified.
    if (out.status != physics::SimStatus::kInterrupted) failed_verification_[task] = 1;
    return std::nullopt;
  }
  PlannedShot ps;
  ps.shot = sc.shot;
  ps.cut = sc.cut;
  ps.object_ball = cand.object;
  ps.pocket = static_cast<physics::PocketId>(out.object_pocket);
  ps.pot_probability = sc.pot_estimate;
  ps.pocket_probability = sc.pot_estimate;
  ps.pot_estimate = sc.pot_estimate;
  const auto events = w.full.simulator().events();
  ps.events.assign(events.begin(), events.end());
  std::vector<Vec2> finals;
  for (const physics::BallState& b : w.full.final_balls()) finals.push_back(b.r);
  ps.cue_ball_end = finals[static_cast<size_t>(cue_)];
  const Leave leave = ScoreLeave(table_, on_, cand.object, finals, out.potted, sc.pot_estimate, after_ctx_,
                                 settings_);
  ps.position_value = leave.position.value;
  ps.next_ball = leave.next_ball;
  ps.search_score = leave.score;
  ps.score = leave.score;
  return ps;
}

// Search and verify, candidates across the workers; reports each verified shot that
// beats the best so far.
void PlanRun::SearchAndVerify() {
  const size_t n = chosen_.size();
  AddWorkers(std::min(request_.threads, static_cast<int>(n)));
  found_.assign(n, std::nullopt);
  failed_verification_.assign(n, 0);
  std::vector<int> search_simulations(n, 0);
  std::vector<char> interrupted(n, 0);
  std::mutex progress_mutex;
  double best_reported = -std::numeric_limits<double>::infinity();
  ParallelFor(request_.threads, static_cast<int>(n), [&](int task, int worker) {
    const size_t t = static_cast<size_t>(task);
    Worker& w = *workers_[static_cast<size_t>(worker)];
    const Candidate& cand = *chosen_[t];
    SearchSettings s = settings_;
    s.global_evaluations = static_cast<int>(std::lround(evaluations_[t] * config_.global_share));
    s.local_evaluations = evaluations_[t] - s.global_evaluations;
    const SearchResult r = SearchCandidate(table_, on_, cand, ctx_, s, w.search, schedule_.search);
    w.evaluations += r.evaluations;
    search_simulations[t] = r.simulations;
    interrupted[t] = r.status == SearchStatus::kInterrupted;
    if (!r.best || schedule_.final.Due()) return;
    found_[t] = Verify(w, cand, *r.best, t);
    if (!found_[t] || request_.progress == nullptr) return;
    std::lock_guard<std::mutex> lock(progress_mutex);
    if (found_[t]->score > best_reported) {
      best_reported = found_[t]->score;
      request_.progress(*found_[t], request_.progress_context);
    }
  });
  for (size_t i = 0; i < n; ++i) {
    answer_.simulations += search_simulations[i] + (found_[i] || failed_verification_[i] ? 1 : 0);
    answer_.verification_failures += failed_verification_[i];
    answer_.deadline_hit = answer_.deadline_hit || interrupted[i] != 0;
    if (found_[i]) shots_.push_back(std::move(*found_[i]));
  }
  for (const auto& w : workers_) answer_.evaluations += w->evaluations;
  answer_.verified = static_cast<int>(shots_.size());
  // Search order: by the nominal objective (stable: ties keep candidate order).
  std::stable_sort(shots_.begin(), shots_.end(),
                   [](const PlannedShot& a, const PlannedShot& b) { return a.search_score > b.search_score; });
}

// Monte Carlo of the best few, blocks across the workers; the final ranking is by
// the Monte Carlo mean objective.
void PlanRun::RankByMonteCarlo() {
  const int ranked = std::min(static_cast<int>(shots_.size()),
                              std::max(request_.max_shots + 2, config_.min_ranked));
  int blocks = (request_.monte_carlo_samples + kBlock - 1) / kBlock;
  if (ranked > 0) blocks = std::min(blocks, static_cast<int>(schedule_.monte_carlo_simulations / (ranked * kBlock)));
  blocks = std::max(blocks, request_.monte_carlo_samples > 0 ? 1 : 0);
  if (ranked == 0 || blocks == 0 || schedule_.monte_carlo.Due()) return;
  AddWorkers(std::min(request_.threads, ranked * blocks));
  std::vector<MonteCarloTally> tallies(static_cast<size_t>(ranked * blocks));
  ParallelFor(request_.threads, ranked * blocks, [&](int task, int worker) {
    const int s = task / blocks, b = task % blocks;
    const PlannedShot& ps = shots_[static_cast<size_t>(s)];
    // Streams keyed by the shot itself (object, pocket) and the block, so a shot's
    // samples do not depend on the other shots ranked with it.
    const std::uint64_t seed = DeriveSeed(
        request_.seed, static_cast<std::uint64_t>(ps.object_ball) * 8 + static_cast<std::uint64_t>(ps.pocket),
        static_cast<std::uint64_t>(b));
    tallies[static_cast<size_t>(task)] =
        RunSamples(table_, on_, ps.object_ball, ps.pocket, ps.shot, ctx_, settings_,
                   workers_[static_cast<size_t>(worker)]->full, schedule_.monte_carlo, seed, kBlock);
  });
  for (int s = 0; s < ranked; ++s) {
    MonteCarloTally t;
    for (int b = 0; b < blocks; ++b) t.Add(tallies[static_cast<size_t>(s * blocks + b)]);
    answer_.simulations += t.samples;
    answer_.deadline_hit = answer_.deadline_hit || t.interrupted;
    PlannedShot& ps = shots_[static_cast<size_t>(s)];
    if (t.samples > 0) {
      ps.monte_carlo_samples = t.samples;
      ps.pot_probability = t.success_rate();
      ps.pocket_probability = t.pocket_rate();
      ps.score = t.mean_score();
    }
  }
  // Shots without samples keep their nominal score, below any sampled competitor in
  // practice.
  std::stable_sort(shots_.begin(), shots_.begin() + ranked,
                   [](const PlannedShot& a, const PlannedShot& b) { return a.score > b.score; });
}

// The answer's shots, status and reason.
void PlanRun::Conclude() {
  if (static_cast<int>(shots_.size()) > request_.max_shots) shots_.resize(static_cast<size_t>(request_.max_shots));
  answer_.shots = std::move(shots_);
  const bool cancelled = request_.cancel != nullptr && request_.cancel->load();
  if (!answer_.shots.empty()) {
    answer_.status = cancelled ? PlanStatus::kCancelled : PlanStatus::kOk;
    if (cancelled) answer_.reason = "cancelled: the best shots found so far";
  } else if (cancelled) {
    answer_.status = PlanStatus::kCancelled;
    answer_.reason = "cancelled before any shot was verified";
  } else if (answer_.deadline_hit && answer_.verified == 0) {
    const bool deadline = schedule_.deadline_binds && Clock::now() >= request_.deadline;
    answer_.status = deadline ? PlanStatus::kDeadline : PlanStatus::kBudgetSpent;
    answer_.reason = std::string(deadline ? "the caller's deadline" : "the time budget") +
                     " ran out before any shot was verified (" + std::to_string(answer_.searched) +
                     " candidates started)";
  } else {
    answer_.status = PlanStatus::kNoPot;
    answer_.reason = "no pot found: the search of " + std::to_string(answer_.searched) + " of " +
                     std::to_string(answer_.candidates) +
                     " candidate pots found no shot that pots the ball without a foul";
    if (answer_.verification_failures > 0) {
      answer_.reason += " (" + std::to_string(answer_.verification_failures) + " failed the full-fidelity check)";
    }
  }
}

}  // namespace

const char* ToString(ShotKind kind) {
  switch (kind) {
    case ShotKind::kPot: return "POT";
    case ShotKind::kSafety: return "SAFETY";
    case ShotKind::kEscape: return "ESCAPE";
    case ShotKind::kBreakOff: return "BREAK_OFF";
  }
  return "UNKNOWN";
}

const char* ToString(PotRoute route) {
  switch (route) {
    case PotRoute::kDirect: return "DIRECT";
    case PotRoute::kPlant: return "PLANT";
    case PotRoute::kDouble: return "DOUBLE";
    case PotRoute::kKick: return "KICK";
  }
  return "UNKNOWN";
}

const char* ToString(PlanStatus s) {
  switch (s) {
    case PlanStatus::kOk: return "ok";
    case PlanStatus::kNoPot: return "no pot";
    case PlanStatus::kInvalidRequest: return "invalid request";
    case PlanStatus::kBudgetSpent: return "budget spent";
    case PlanStatus::kDeadline: return "deadline";
    case PlanStatus::kCancelled: return "cancelled";
  }
  return "unknown";
}

double PlannerConfig::SearchWeight(int rank) const {
  return std::max(min_search_weight, std::pow(0.5, rank / search_weight_band));
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

PlanAnswer Planner::Plan(const PlanRequest& request) const { return PlanRun(*this, request).Run(); }

}  // namespace snooker::planner
