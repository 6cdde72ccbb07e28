#include "planner/planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>

#include "planner/break_off.h"
#include "planner/fallback.h"
#include "planner/layout.h"
#include "planner/outlook.h"
#include "planner/parallel.h"
#include "planner/placement.h"
#include "planner/random.h"
#include "planner/robustness.h"
#include "planner/routes.h"
#include "planner/safety.h"
#include "planner/validate.h"

namespace snooker::planner {
namespace {

using Clock = std::chrono::steady_clock;
using physics::Vec2;

// Monte Carlo samples come in blocks with their own random streams.
constexpr int kBlock = 8;

// The kinds and routes a request limits the plan to, in the API's names: "kinds
// SAFETY, ESCAPE; routes PLANT" (each part only when some are left out).
std::string AskedFor(const PlanRequest& r) {
  std::string out;
  auto part = [&](const char* label, auto set, int count, auto as) {
    if (set == decltype(set){}) return;
    out += out.empty() ? "" : "; ";
    out += label;
    bool first = true;
    for (int k = 0; k < count; ++k) {
      if (!set.Has(as(k))) continue;
      out += (first ? " " : ", ") + std::string(ToString(as(k)));
      first = false;
    }
  };
  part("kinds", r.kinds, kShotKindCount, [](int k) { return static_cast<ShotKind>(k); });
  part("routes", r.routes, kPotRouteCount, [](int k) { return static_cast<PotRoute>(k); });
  return out;
}

// One worker's simulators, reused across its tasks.
struct Worker {
  Worker(const physics::TableModel& table, const Planner::Config& c)
      : search(table, c.search), full(table, c.full) {}
  ShotSimulator search;
  ShotSimulator full;
  SampleScratch samples;
  LeaveScratch leave;  // the searches' tables left
  std::int64_t evaluations = 0;
};

// When each stage of a plan must end, and the simulations it may run.
struct Schedule {
  StopControl search;
  StopControl lookahead;
  StopControl monte_carlo;
  StopControl final;
  StopControl caller;  // the caller's deadline alone (the fallback's)
  double search_simulations = 0;
  double lookahead_simulations = 0;
  double monte_carlo_simulations = 0;
  std::int64_t simulation_cap = 0;
  // The caller's deadline, not the budget, is what ends the work.
  bool deadline_binds = false;
};

// Whether the clock or a cancel stopped any of a plan's work before its simulation
// caps did. Each piece of work bounded by a deadline says when it ended: one that
// ended before its deadline, uncancelled, never saw either (every check it made came
// before its end), so it did what the caps alone would have had it do.
class CutWatch {
 public:
  // Work bounded by `stop` ends now: stop.Due(), remembered when true.
  bool Ended(const StopControl& stop) {
    if (!stop.Due()) return false;
    Cut();
    return true;
  }
  void Cut() { cut_.store(true, std::memory_order_relaxed); }
  bool cut() const { return cut_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> cut_{false};
};

Schedule MakeSchedule(const PlannerConfig& config, const PlanRequest& request, Clock::time_point start) {
  const auto budget = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(request.time_budget));
  // The time the plan has: its budget, or less when the caller's deadline comes
  // first. The stages share out that time, so that a deadline shorter than the
  // budget still leaves the verification and the Monte Carlo their parts of it.
  const Clock::duration window =
      request.deadline - start < budget ? std::max(Clock::duration::zero(), request.deadline - start) : budget;
  // The work ends a little before the budget: the last simulation in flight, the
  // threads' join and the answer's assembly come after it.
  const Clock::time_point budget_end =
      start + std::chrono::duration_cast<Clock::duration>(budget * config.end_share);
  const Clock::time_point end =
      std::min(request.deadline, start + std::chrono::duration_cast<Clock::duration>(window * config.end_share));
  auto at = [&](double share) {
    return std::min(end, start + std::chrono::duration_cast<Clock::duration>(window * share));
  };
  // Lookahead takes its share out of the search's: one-ply and two-ply plans spend
  // the same time.
  const double lookahead = request.lookahead && request.position_play ? config.lookahead_share : 0.0;
  Schedule s;
  s.search = {at(config.search_share - lookahead), request.cancel};
  s.lookahead = {at(config.search_share), request.cancel};
  s.monte_carlo = {at(config.search_share + config.monte_carlo_share), request.cancel};
  s.final = {end, request.cancel};
  s.caller = {request.deadline, request.cancel};
  s.deadline_binds = request.deadline < budget_end;
  // Whole simulations, so that a request whose max_simulations is this plan's cap
  // shares the work out exactly as this one does.
  s.simulation_cap = request.max_simulations > 0
                         ? request.max_simulations
                         : std::max<std::int64_t>(1, std::llround(config.simulations_per_ms *
                                                                  std::chrono::duration<double, std::milli>(window).count() *
                                                                  request.threads));
  const double total = static_cast<double>(s.simulation_cap);
  s.search_simulations = total * (config.search_share - lookahead);
  s.lookahead_simulations = total * lookahead;
  s.monte_carlo_simulations = total * config.monte_carlo_share;
  return s;
}

// A route's candidate (routes.h) as the search takes it: plants and doubles aim by
// the cut on their first ball within its bracket, kicks and escapes by the heading
// within its bracket; speeds wide enough for the route's travel.
Candidate FromRoute(const RouteCandidate& r) {
  Candidate c;
  c.kind = KindOf(r.route);
  c.route = PotRouteOf(r.route).value_or(PotRoute::kDirect);
  c.object = c.kind == ShotKind::kPot ? r.potted_ball : r.first_ball;
  c.first = c.kind == ShotKind::kPot ? r.first_ball : -1;
  if (r.pocket) c.pocket = *r.pocket;
  c.estimate.probability = r.probability;
  c.estimate.sigma = r.sigma;
  c.estimate.heading_gain = r.heading_gain;
  c.estimate.window = r.window;
  c.estimate.distance = r.distance;
  c.estimate.object_direction = r.object_direction;
  c.cue_margin = r.cue_margin;
  c.aim_ball = r.first_ball;
  if (r.aim == AimBy::kCut) {
    c.aim = AimMode::kCut;
    c.aim_base = r.cut + 0.5 * (r.cut_bracket.lo + r.cut_bracket.hi);
    c.aim_range = std::max(0.5 * r.cut_bracket.width(), 1e-3);
  } else {
    c.aim = AimMode::kHeading;
    c.aim_base = r.heading + 0.5 * (r.heading_bracket.lo + r.heading_bracket.hi);
    c.aim_range = std::max(0.5 * r.heading_bracket.width(), 1e-3);
  }
  c.speed_lo = c.kind == ShotKind::kPot ? 1.0 : 0.8;
  c.speed_hi = c.kind == ShotKind::kPot ? 5.0 : 4.0;
  return c;
}

// A break-off (break_off.h) as the search takes it: the cut on the end red within
// its clear range (at most 6 deg either side of the nominal), firm.
Candidate FromBreakOff(const BreakOffCandidate& b, int table) {
  Candidate c;
  c.kind = ShotKind::kBreakOff;
  c.object = b.target;
  c.aim = AimMode::kCut;
  const double range = 6 * physics::kPi / 180;
  const double lo = std::max(b.cut_lo, b.cut - range), hi = std::min(b.cut_hi, b.cut + range);
  c.aim_base = 0.5 * (lo + hi);
  c.aim_range = std::max(0.5 * (hi - lo), 1e-3);
  c.speed_lo = b.soft ? 0.5 * b.speed : b.speed - 1.0;
  c.speed_hi = b.soft ? 1.5 * b.speed : b.speed + 1.0;
  c.table = table;
  c.cue_start = b.placement;
  c.estimate.probability = 1;
  return c;
}

// The route a pot took, from its run: a plant when the cue ball hit another ball
// first, a kick when the cue ball met a cushion first, a double when the object ball
// met one before dropping, else direct.
PotRoute RouteOf(const ShotOutcome& out, int object) {
  if (out.first_hit != object) return PotRoute::kPlant;
  if (out.cue_cushions_first > 0) return PotRoute::kKick;
  if (out.object_cushions > 0) return PotRoute::kDouble;
  return PotRoute::kDirect;
}

// One plan from request to answer, as its stages: Prepare (validation, the ball on,
// the candidates of every kind the request allows), Allocate (which candidates get
// how much search), SearchAndVerify, RankByMonteCarlo, Conclude.
class PlanRun {
 public:
  PlanRun(const Planner& planner, const PlanRequest& request)
      : planner_(planner), config_(planner.config()), request_(request), table_(request.table),
        start_(Clock::now()) {}

  PlanAnswer Run() {
    if (Prepare()) {
      Allocate();
      SearchAndVerify();
      Fallback();
      LookAhead();
      RankByMonteCarlo();
      Conclude();
    }
    answer_.simulation_cap = schedule_.simulation_cap;
    answer_.cut_short = cut_.cut();
    answer_.elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    return std::move(answer_);
  }

 private:
  bool Prepare();
  void AddPots();
  void AddRoutes();
  void AddOthers();
  bool AddBreakOff();
  int TableWithCue();
  void Allocate();
  void SearchAndVerify();
  ShotSetup SetupFor(const Candidate& cand) const;
  ShotSetup SetupFor(const PlannedShot& ps) const;
  std::optional<PlannedShot> Verify(Worker& w, const Candidate& cand, const ShotCandidate& sc, size_t task,
                                    const physics::Interrupt& interrupt);
  std::vector<const ShotCandidate*> Alternatives(const Candidate& cand, const SearchResult& r) const;
  void Fallback();
  void LookAhead();
  double NextShotValue(Worker& w, const PlannedShot& ps, int evaluations, int* simulations) const;
  // The fallback's scan runs when the request takes a stroke that need not pot: a
  // safety, an escape or (with none of them legal) a foul.
  bool FallbackAllowed() const {
    return request_.kinds.Has(ShotKind::kSafety) || request_.kinds.Has(ShotKind::kEscape) ||
           request_.kinds.Has(ShotKind::kFoul);
  }
  std::string FallbackOutcome() const;
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
  PotContext ctx_;
  PotContext after_ctx_;  // the next shot's: vision sees the moved balls afresh
  SearchSettings settings_;
  Schedule schedule_;
  CutWatch cut_;
  // The tables candidates play on: the request's first, then one per placement of
  // the cue ball in hand (the cue ball last).
  std::vector<TableState> tables_;
  static constexpr int kNotPlaced = -2;
  int cue_table_ = kNotPlaced;  // TableWithCue's table, once made
  std::vector<Candidate> candidates_;
  std::string no_candidates_;  // why there were none to search, when so
  bool fallback_past_budget_ = false;  // the fallback's stroke was verified after the budget
  bool fallback_scanned_ = false;  // the fallback's scan ran to its end
  std::optional<ShotKind> fallback_unasked_;  // the kind of its stroke, when not one asked for
  CandidateSet pots_;  // the direct pots' pruning counts, for the reason
  double best_pot_ = 0;  // the best pot estimate
  LayoutSummary layout_;  // the request's table, for the layout term
  // Allocate: the candidates searched (pots by prior, then the others) and their
  // evaluations.
  std::vector<const Candidate*> chosen_;
  std::vector<int> evaluations_;
  // SearchAndVerify, one slot per chosen candidate.
  std::vector<std::unique_ptr<Worker>> workers_;
  std::vector<std::vector<PlannedShot>> found_;
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
  const auto on = request_.ball_on ? request_.ball_on : OpeningBallOn(table_);
  answer_.ball_on = on;
  if (!on) {
    answer_.status = PlanStatus::kNoPot;
    answer_.reason = "no ball on: the table holds only the cue ball";
    return false;
  }
  on_ = *on;
  ctx_ = planner_.ContextFor(request_);
  LayoutOptions layout;
  layout.pockets = ctx_.pockets;
  layout_ = SummarizeLayout(table_, *config_.table, layout);
  ctx_.layout = &layout_;
  after_ctx_ = ctx_;
  after_ctx_.position_sigma.clear();
  settings_ = config_.search_settings;
  settings_.limits = request_.limits;
  settings_.position_play = request_.position_play;
  if (request_.break_value) settings_.position.continuation = *request_.break_value;
  if (request_.position_spread) settings_.position_spread = *request_.position_spread;
  schedule_ = MakeSchedule(config_, request_, start_);
  tables_.push_back(table_);
  if (!AddBreakOff()) {
    AddPots();
    AddRoutes();
    AddOthers();
  }
  answer_.candidate_pairs = pots_.pairs;
  answer_.candidates = static_cast<int>(candidates_.size());
  if (candidates_.empty()) {
    std::ostringstream why;
    if (!request_.kinds.Has(ShotKind::kPot) || !request_.routes.Has(PotRoute::kDirect)) {
      // Direct pots were not asked for: say what was, which this table does not offer.
      why << "no pot: no candidate for the ball on (" << ToString(on_) << ") among the shots asked for ("
          << AskedFor(request_) << ")";
    } else {
      why << "no pot: none of the " << pots_.pairs << " ball-pocket pairs for the ball on (" << ToString(on_)
          << ") survives pruning";
    }
    for (int k = 1; k < kPruneReasonCount; ++k) {
      if (pots_.pruned[static_cast<size_t>(k)] > 0) {
        why << "; " << ToString(static_cast<PruneReason>(k)) << ": " << pots_.pruned[static_cast<size_t>(k)];
      }
    }
    no_candidates_ = why.str();
    // Nothing to search; the fallback's scan may still find a legal stroke.
    answer_.status = PlanStatus::kNoPot;
    answer_.reason = no_candidates_;
    return FallbackAllowed();
  }
  return true;
}

// Direct pots: from the cue ball where it lies, or from the best places in the D for
// the cue ball in hand (placement.h), each on a table of its own.
void PlanRun::AddPots() {
  if (!request_.kinds.Has(ShotKind::kPot) || !request_.routes.Has(PotRoute::kDirect)) return;
  if (!request_.cue_in_hand) {
    pots_ = EnumerateCandidates(table_, on_, ctx_);
    candidates_.insert(candidates_.end(), pots_.candidates.begin(), pots_.candidates.end());
  } else {
    const auto placed = PlaceForPots(table_, on_, ctx_, settings_.position.continuation);
    for (const PlacedCandidate& p : placed) {
      if (static_cast<int>(tables_.size()) > config_.max_candidates) break;
      tables_.push_back(WithCueBall(table_, p.place));
      Candidate c = p.candidate;
      c.table = static_cast<int>(tables_.size()) - 1;
      candidates_.push_back(c);
      ++pots_.pairs;
    }
  }
  for (const Candidate& c : candidates_) best_pot_ = std::max(best_pot_, c.estimate.probability);
}

// The frame's first shot: with the cue ball in hand and the reds racked, the
// break-off's candidates only (nothing can be potted from the D into the pack).
bool PlanRun::AddBreakOff() {
  if (!request_.kinds.Has(ShotKind::kBreakOff) || !IsBreakOffTable(table_, request_.cue_in_hand, *config_.table)) {
    return false;
  }
  // The soft breaks; with the thin break on, the two alternate: the budget searches
  // only the first few (a break into the pack is a long simulation), and the Monte
  // Carlo then picks between the kinds.
  const std::vector<BreakOffCandidate> soft = SoftBreakCandidates(table_, *config_.table);
  const bool thin_too = request_.thin_break_off.value_or(config_.thin_break_off);
  const std::vector<BreakOffCandidate> thin =
      thin_too ? BreakOffCandidates(table_, *config_.table) : std::vector<BreakOffCandidate>{};
  std::vector<BreakOffCandidate> all;
  for (size_t k = 0; k < std::max(soft.size(), thin.size()); ++k) {
    if (k < soft.size()) all.push_back(soft[k]);
    if (k < thin.size()) all.push_back(thin[k]);
  }
  for (const BreakOffCandidate& b : all) {
    tables_.push_back(WithCueBall(table_, b.placement));
    candidates_.push_back(FromBreakOff(b, static_cast<int>(tables_.size()) - 1));
  }
  return true;
}

// Pots by other routes (plants, doubles, kicks) from where the cue ball lies: the
// likeliest few of each.
void PlanRun::AddRoutes() {
  if (!request_.kinds.Has(ShotKind::kPot) || request_.cue_in_hand) return;
  const int cue = table_.cue_index();
  const struct {
    PotRoute route;
    std::vector<RouteCandidate> (*enumerate)(const TableState&, int, BallOn, const PotContext&, const RouteOptions&,
                                             RouteStats*);
  } routes[] = {{PotRoute::kPlant, &EnumeratePlants},
                {PotRoute::kDouble, &EnumerateDoubles},
                {PotRoute::kKick, &EnumerateKicks}};
  for (const auto& r : routes) {
    if (!request_.routes.Has(r.route)) continue;
    const std::vector<RouteCandidate> found = r.enumerate(table_, cue, on_, ctx_, RouteOptions{}, nullptr);
    for (size_t i = 0; i < found.size() && static_cast<int>(i) < config_.routes_each; ++i) {
      candidates_.push_back(FromRoute(found[i]));
    }
  }
}

// The table the shots that need only a legal place for the cue ball play on: the
// request's, or with the cue ball in hand one with it placed centrally in the D.
// -1 when the D has no room.
int PlanRun::TableWithCue() {
  if (!request_.cue_in_hand) return 0;
  if (cue_table_ != kNotPlaced) return cue_table_;
  const auto place = FreePlaceInTheD(table_, *config_.table);
  cue_table_ = -1;
  if (place) {
    tables_.push_back(WithCueBall(table_, *place));
    cue_table_ = static_cast<int>(tables_.size()) - 1;
  }
  return cue_table_;
}

// Shots of other kinds when no pot is near certain: safeties, and escapes when the
// cue ball is snookered.
void PlanRun::AddOthers() {
  const bool safeties = request_.kinds.Has(ShotKind::kSafety), escapes = request_.kinds.Has(ShotKind::kEscape);
  if ((!safeties && !escapes) || best_pot_ >= config_.safety_below) return;
  const int t = TableWithCue();
  if (t < 0) return;
  const TableState& table = tables_[static_cast<size_t>(t)];
  const int cue = table.cue_index();
  const int touching = TouchingBallOn(table, on_, *config_.table);
  std::vector<Candidate> others;
  if (safeties) others = SafetyCandidates(table, cue, on_, ctx_, touching, t, SafetyOptions{});
  if (escapes && CheckSnooker(table, cue, on_, ctx_, OutlookOptions{}.contacts).snookered) {
    const std::vector<RouteCandidate> found = EnumerateEscapes(table, cue, on_, ctx_, RouteOptions{}, nullptr);
    for (size_t i = 0; i < found.size() && static_cast<int>(i) < config_.routes_each; ++i) {
      Candidate c = FromRoute(found[i]);
      c.table = t;
      others.push_back(c);
    }
  }
  for (Candidate& c : others) {
    if (t > 0) c.cue_start = table.balls[static_cast<size_t>(cue)].position;
  }
  if (static_cast<int>(others.size()) > config_.max_others) others.resize(static_cast<size_t>(config_.max_others));
  candidates_.insert(candidates_.end(), others.begin(), others.end());
}

// How much search each candidate gets. Pots by their prior, the estimated points p
// (value + continuation), the most promising most, hopeless ones none; the other
// kinds share what the pots leave them, more the less likely the best pot is.
void PlanRun::Allocate() {
  const double continuation = settings_.position.continuation;
  auto prior = [&](const Candidate& c) {
    const TableState& t = tables_[static_cast<size_t>(c.table)];
    return c.estimate.probability * (Value(t.balls[static_cast<size_t>(c.object)].kind) + continuation);
  };
  std::vector<const Candidate*> pots, others;
  for (const Candidate& c : candidates_) (c.kind == ShotKind::kPot ? pots : others).push_back(&c);
  std::stable_sort(pots.begin(), pots.end(), [&](const Candidate* a, const Candidate* b) { return prior(*a) > prior(*b); });
  const double pot_share = others.empty() ? 1.0 : pots.empty() ? 0.0 : 0.5 + 0.4 * best_pot_;
  const double pot_simulations = schedule_.search_simulations * pot_share;
  std::vector<double> weight;
  for (const Candidate* c : pots) {
    if (static_cast<int>(chosen_.size()) >= config_.max_candidates) break;
    if (!chosen_.empty() && prior(*c) < config_.min_prior_share * prior(*pots.front())) break;
    chosen_.push_back(c);
    weight.push_back(config_.SearchWeight(static_cast<int>(chosen_.size()) - 1));
  }
  // Drop the least promising until every pot gets a worthwhile search.
  for (;;) {
    double sum = 0;
    for (double w : weight) sum += w;
    evaluations_.assign(chosen_.size(), 0);
    bool enough = true;
    for (size_t i = 0; i < chosen_.size(); ++i) {
      evaluations_[i] = static_cast<int>(pot_simulations * weight[i] / sum);
      enough = enough && evaluations_[i] >= config_.min_evaluations;
    }
    if (enough || chosen_.size() <= 1) break;
    chosen_.pop_back();
    weight.pop_back();
  }
  const int other_evaluations =
      others.empty() ? 0
                     : static_cast<int>(schedule_.search_simulations * (1 - pot_share) / static_cast<double>(others.size()));
  for (const Candidate* c : others) {
    chosen_.push_back(c);
    evaluations_.push_back(other_evaluations);
  }
  for (int& e : evaluations_) e = std::max(e, config_.min_evaluations);
  answer_.searched = static_cast<int>(chosen_.size());
}

ShotSetup PlanRun::SetupFor(const Candidate& cand) const {
  const TableState& table = tables_[static_cast<size_t>(cand.table)];
  const int cue = table.cue_index();
  return {&table, cue, cand.object, cand.pocket, on_, cand.kind, cand.first,
          TouchingBallOn(table, on_, *config_.table)};
}

namespace {

// `setup` as the pot of `object` into `pocket` that a stroke searched as another kind
// turned out to be: the first ball it hit names a plant when that is another ball.
ShotSetup AsPot(ShotSetup setup, int object, physics::PocketId pocket, int first_hit) {
  setup.kind = ShotKind::kPot;
  setup.object = object;
  setup.pocket = pocket;
  setup.first = first_hit != object ? first_hit : -1;
  return setup;
}

}  // namespace

// A verified shot's setup: its candidate's, unless verification found it a pot of
// another kind's search (Verify), which its labels then describe.
ShotSetup PlanRun::SetupFor(const PlannedShot& ps) const {
  const Candidate& cand = candidates_[static_cast<size_t>(ps.source)];
  const ShotSetup setup = SetupFor(cand);
  if (ps.kind == cand.kind) return setup;
  return AsPot(setup, ps.object_ball, ps.pocket, ps.first_ball);
}

namespace {

// The first ball on that `out` dropped legally (the visit goes on), or -1.
int LegalPotOf(const TableState& table, BallOn on, const ShotOutcome& out) {
  const std::optional<BallKind> nominated =
      out.first_hit >= 0 ? std::optional<BallKind>(table.balls[static_cast<size_t>(out.first_hit)].kind) : std::nullopt;
  const ShotJudgement j = JudgeShot(table, on, nominated, out.first_hit, out.potted);
  if (j.legal_pots == 0 || !j.potted_kind) return -1;
  for (const int i : out.potted) {
    if (table.balls[static_cast<size_t>(i)].kind == *j.potted_kind) return i;
  }
  return -1;
}

}  // namespace

// The candidate's best shot simulated again at full fidelity, to the end. Its labels
// (kind, route, object ball, pocket) are what this simulation did, not what was
// intended: a safety or an escape that drops a ball on continues the visit, so it is
// that ball's pot (by the route it took), simulated again as one so that its object
// ball is followed (and the Monte Carlo counts its drops), or dropped when the
// request does not take such a pot.
std::optional<PlannedShot> PlanRun::Verify(Worker& w, const Candidate& cand, const ShotCandidate& sc,
                                           size_t task, const physics::Interrupt& interrupt) {
  // Every stroke answered is one the robot can play; the searches make only such
  // strokes, and this holds them to it.
  if (!CueWithinLimits(sc.cue, settings_.limits)) {
    failed_verification_[task] = 1;
    return std::nullopt;
  }
  ShotSetup setup = SetupFor(cand);
  const TableState& table = *setup.table;
  const ShotOutcome* run = &w.full.Run(setup, sc.shot, {}, ShotSimulator::Mode::kFull, interrupt);
  bool relabelled = false;
  if ((cand.kind == ShotKind::kSafety || cand.kind == ShotKind::kEscape) && run->success) {
    if (const int dropped = LegalPotOf(table, on_, *run); dropped >= 0) {
      if (!request_.kinds.Has(ShotKind::kPot)) {
        failed_verification_[task] = 1;
        return std::nullopt;
      }
      const int pocket = w.full.simulator().pocket_of(dropped);
      setup = AsPot(setup, dropped, static_cast<physics::PocketId>(pocket), run->first_hit);
      run = &w.full.Run(setup, sc.shot, {}, ShotSimulator::Mode::kFull, interrupt);
      relabelled = true;
    }
  }
  const ShotOutcome& out = *run;
  const bool pot = setup.kind == ShotKind::kPot;
  const PotRoute route = pot ? RouteOf(out, setup.object) : PotRoute::kDirect;
  // A foul stroke (the fallback's last resort) is what it says when it fouls.
  const bool foul = setup.kind == ShotKind::kFoul;
  const bool does_its_job = foul ? out.status == physics::SimStatus::kAtRest && out.foul != Foul::kNone &&
                                       out.foul != Foul::kSimulationFailed
                                 : out.success && (!pot || request_.routes.Has(route));
  if (!does_its_job) {
    // An interrupted check says nothing about the shot: it is dropped unverified.
    if (out.status != physics::SimStatus::kInterrupted) failed_verification_[task] = 1;
    return std::nullopt;
  }
  PlannedShot ps;
  ps.kind = setup.kind;
  ps.route = route;
  ps.cue_start = cand.cue_start;
  ps.cue = sc.cue;
  ps.shot = sc.shot;
  ps.cut = sc.cut;
  ps.first_ball = out.first_hit;
  ps.object_ball = pot || foul ? setup.object : out.first_hit;
  if (pot) ps.pocket = static_cast<physics::PocketId>(out.object_pocket);
  // A relabelled stroke has no estimate from its search (which judged another kind):
  // its nominal run drops the ball, and the Monte Carlo gives the probability.
  ps.pot_probability = pot ? (relabelled ? 1.0 : sc.pot_estimate) : 0;
  ps.foul_probability = foul ? 1.0 : 0.0;  // the nominal run's, until the Monte Carlo's
  ps.pocket_probability = ps.pot_probability;
  ps.pot_estimate = ps.pot_probability;
  const auto events = w.full.simulator().events();
  ps.events.assign(events.begin(), events.end());
  std::vector<Vec2> finals;
  for (const physics::BallState& b : w.full.final_balls()) finals.push_back(b.r);
  for (size_t i = 0; i < finals.size(); ++i) {
    const int pocket = w.full.simulator().pocket_of(static_cast<int>(i));
    ps.balls_end.push_back({finals[i], pocket >= 0 ? std::optional<physics::PocketId>(static_cast<physics::PocketId>(pocket))
                                                   : std::nullopt});
  }
  ps.cue_ball_end = finals[static_cast<size_t>(setup.cue)];
  Leave leave;
  if (pot) {
    leave = ScoreLeave(table, on_, setup.object, finals, out.potted, ps.pot_probability, after_ctx_, settings_,
                       &w.leave);
  } else if (foul) {
    leave.score = MonteCarloScore(setup, out, finals, after_ctx_, settings_, &w.leave).score;
  } else {
    leave = ScoreSafety(table, on_, out.first_hit, finals, out.potted, after_ctx_, settings_, &w.leave);
    if (const std::optional<Outlook>& o = leave.opponent) {
      ps.opponent = OpponentLeave{o->pot_probability, o->expected_points, o->snooker.snookered, o->foul_probability,
                                  o->penalty};
    }
  }
  ps.position_value = leave.position.value;
  ps.position_points = leave.position.expected_points;
  ps.next_ball = leave.next_ball;
  ps.search_score = leave.score;
  ps.score = leave.score;
  ps.source = static_cast<int>(&cand - candidates_.data());
  return ps;
}

// The shots of a search worth verifying: its best, and for a pot the best of each
// other spin class (stun, follow, screw) that scores at least alternative_share of
// it: the same pot played differently, for the caller to choose from.
std::vector<const ShotCandidate*> PlanRun::Alternatives(const Candidate& cand, const SearchResult& r) const {
  std::vector<const ShotCandidate*> out = {&*r.best};
  if (cand.kind != ShotKind::kPot || r.best->score <= 0) return out;
  for (const auto& alt : r.by_spin) {
    if (alt && alt->shot.topspin != r.best->shot.topspin && alt->score >= config_.alternative_share * r.best->score) {
      out.push_back(&*alt);
    }
  }
  return out;
}

// Search and verify, candidates across the workers; reports each verified shot that
// beats the best so far.
void PlanRun::SearchAndVerify() {
  const size_t n = chosen_.size();
  AddWorkers(std::min(request_.threads, static_cast<int>(n)));
  found_.assign(n, {});
  failed_verification_.assign(n, 0);
  std::vector<int> search_simulations(n, 0), verifications(n, 0);
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
    const SearchResult r = SearchCandidate(tables_[static_cast<size_t>(cand.table)], on_, cand, ctx_, s, w.search,
                                           schedule_.search, &w.leave);
    if (r.status == SearchStatus::kInterrupted) cut_.Cut();  // NLopt's own clock too (search.h)
    cut_.Ended(schedule_.search);
    w.evaluations += r.evaluations;
    search_simulations[t] = r.simulations;
    interrupted[t] = r.status == SearchStatus::kInterrupted;
    if (!r.best || cut_.Ended(schedule_.final)) return;
    for (const ShotCandidate* sc : Alternatives(cand, r)) {
      ++verifications[t];
      if (auto ps = Verify(w, cand, *sc, t, schedule_.final.AsInterrupt())) found_[t].push_back(std::move(*ps));
    }
    cut_.Ended(schedule_.final);
    if (found_[t].empty() || request_.progress == nullptr) return;
    std::lock_guard<std::mutex> lock(progress_mutex);
    if (found_[t].front().score > best_reported) {
      best_reported = found_[t].front().score;
      request_.progress(found_[t].front(), request_.progress_context);
    }
  });
  for (size_t i = 0; i < n; ++i) {
    answer_.simulations += search_simulations[i] + verifications[i];
    answer_.verification_failures += failed_verification_[i];
    answer_.deadline_hit = answer_.deadline_hit || interrupted[i] != 0;
    for (PlannedShot& ps : found_[i]) shots_.push_back(std::move(ps));
  }
  for (const auto& w : workers_) answer_.evaluations += w->evaluations;
  answer_.verified = static_cast<int>(shots_.size());
  // Search order: pots by their nominal objective (stable: ties keep candidate
  // order), then the other kinds by theirs.
  std::stable_sort(shots_.begin(), shots_.end(), [](const PlannedShot& a, const PlannedShot& b) {
    const bool pa = a.kind == ShotKind::kPot, pb = b.kind == ShotKind::kPot;
    if (pa != pb) return pa;
    return a.search_score > b.search_score;
  });
}

// With no verified shot, a legal stroke by a deterministic scan (fallback.h), when
// the request allows a shot that does not pot: a robot must strike every turn. The
// scan and its verification run until the caller's deadline, not the budget: the
// budget is what the plan aims at, the deadline when the robot must have a stroke.
void PlanRun::Fallback() {
  const bool cancelled = request_.cancel != nullptr && request_.cancel->load();
  if (!shots_.empty() || cancelled || !FallbackAllowed()) return;
  if (cut_.Ended(schedule_.caller)) {
    answer_.deadline_hit = true;  // no time for the scan: the deadline, not the table, left no shot
    return;
  }
  const int t = TableWithCue();
  if (t < 0) return;
  const TableState& table = tables_[static_cast<size_t>(t)];
  AddWorkers(1);
  Worker& w = *workers_.front();
  const physics::Interrupt interrupt = schedule_.caller.AsInterrupt();
  FallbackOptions options;
  options.allow_foul = request_.kinds.Has(ShotKind::kFoul);
  const auto found = FindLegalStroke(table, table.cue_index(), on_, ctx_, settings_, w.full, interrupt, options);
  const bool stopped = cut_.Ended(schedule_.caller);  // what `interrupt` checks, read once
  if (!found) {
    answer_.deadline_hit = answer_.deadline_hit || stopped;
    fallback_scanned_ = !stopped;
    return;
  }
  fallback_scanned_ = true;
  answer_.simulations += found->simulations;
  if (!request_.kinds.Has(found->kind)) {
    // A stroke of a kind the caller did not ask for (an escape when only safeties
    // were, a legal stroke when only fouls were): not answered, the reason says so.
    fallback_unasked_ = found->kind;
    return;
  }
  Candidate c;
  c.kind = found->kind;
  c.object = found->object;
  c.table = t;
  if (t > 0) c.cue_start = table.balls.back().position;
  candidates_.push_back(c);
  failed_verification_.push_back(0);
  ShotCandidate sc;
  sc.cue = found->cue;
  sc.shot = found->shot;
  sc.score = found->score;
  ++answer_.simulations;
  if (auto ps = Verify(w, candidates_.back(), sc, failed_verification_.size() - 1, interrupt)) {
    shots_.push_back(std::move(*ps));
    fallback_past_budget_ = cut_.Ended(schedule_.final);
  }
  cut_.Ended(schedule_.caller);
  answer_.verified = static_cast<int>(shots_.size());
}

// How the next shot's probability, searched rather than estimated, changes what a
// pot's leave is worth: for the next ball's likeliest pot, a short search finds the
// probability the simulated shot really has; the position's value
// (position.h) moves by the first weight times the change in probability times the
// ball's points (value + continuation), so the currency stays the estimate's. A
// search that finds no pot says little against the estimate: no change then.
double PlanRun::NextShotValue(Worker& w, const PlannedShot& ps, int evaluations, int* simulations) const {
  const Candidate& cand = candidates_[static_cast<size_t>(ps.source)];
  const TableState& table = tables_[static_cast<size_t>(cand.table)];
  std::vector<Vec2> finals;
  std::vector<int> potted;
  for (size_t i = 0; i < ps.balls_end.size(); ++i) {
    finals.push_back(ps.balls_end[i].position);
    if (ps.balls_end[i].pocket) potted.push_back(static_cast<int>(i));
  }
  const TableState after = ApplyShot(table, on_, finals, potted, false, *config_.table);
  const auto next_on = NextBallOn(on_, table.balls[static_cast<size_t>(ps.object_ball)].kind, after);
  if (!next_on || after.cue_index() < 0) return 0;
  const CandidateSet next = EnumerateCandidates(after, *next_on, after_ctx_);
  SearchSettings s = settings_;
  s.global_evaluations = static_cast<int>(std::lround(evaluations * config_.global_share));
  s.local_evaluations = evaluations - s.global_evaluations;
  if (next.candidates.empty()) return 0;
  const Candidate& c = next.candidates.front();  // the likeliest next pot
  const SearchResult r = SearchCandidate(after, *next_on, c, after_ctx_, s, w.search, schedule_.lookahead, &w.leave);
  *simulations += r.simulations;
  if (!r.best) return 0;
  const double points = Value(after.balls[static_cast<size_t>(c.object)].kind) + settings_.position.continuation;
  return settings_.position.weights[0] * (r.best->pot_estimate - c.estimate.probability) * points;
}

// Two-ply: for the best few pots, the next shot searched from the table each leaves
// (NextShotValue) replaces the position's estimate in their scores; the Monte Carlo
// then ranks with that correction.
void PlanRun::LookAhead() {
  if (!request_.lookahead || !request_.position_play || cut_.Ended(schedule_.lookahead)) return;
  std::vector<PlannedShot*> pots;
  for (PlannedShot& ps : shots_) {
    if (ps.kind == ShotKind::kPot && static_cast<int>(pots.size()) < config_.lookahead_shots) pots.push_back(&ps);
  }
  if (pots.empty()) return;
  const int tasks = static_cast<int>(pots.size());
  const int evaluations =
      std::max(config_.min_evaluations, static_cast<int>(schedule_.lookahead_simulations / tasks));
  AddWorkers(std::min(request_.threads, tasks));
  std::vector<double> value(pots.size(), 0);
  std::vector<int> simulations(pots.size(), 0);
  ParallelFor(request_.threads, tasks, [&](int task, int worker) {
    const size_t t = static_cast<size_t>(task);
    value[t] = NextShotValue(*workers_[static_cast<size_t>(worker)], *pots[t], evaluations, &simulations[t]);
  });
  cut_.Ended(schedule_.lookahead);
  for (size_t i = 0; i < pots.size(); ++i) {
    answer_.simulations += simulations[i];
    PlannedShot& ps = *pots[i];
    ps.lookahead = value[i];
    ps.search_score += ps.pot_probability * ps.lookahead;
    ps.score = ps.search_score;
  }
  std::stable_sort(shots_.begin(), shots_.end(), [](const PlannedShot& a, const PlannedShot& b) {
    const bool pa = a.kind == ShotKind::kPot, pb = b.kind == ShotKind::kPot;
    if (pa != pb) return pa;
    return a.search_score > b.search_score;
  });
}

// Monte Carlo of the best few pots and the best others, blocks across the workers;
// the final ranking is by the Monte Carlo mean of what each shot is worth, in
// points, misses and fouls included (robustness.h), so that pots and safeties
// compare.
void PlanRun::RankByMonteCarlo() {
  // The ranked shots: the first pots and the first others, moved to the front.
  const int pots_ranked = std::max(request_.max_shots + 2, config_.min_ranked);
  std::vector<PlannedShot> ranked, rest;
  int pots = 0, others = 0;
  for (PlannedShot& s : shots_) {
    const bool pot = s.kind == ShotKind::kPot;
    const bool take = pot ? pots++ < pots_ranked : others++ < config_.ranked_others;
    (take ? ranked : rest).push_back(std::move(s));
  }
  const int n = static_cast<int>(ranked.size());
  shots_ = std::move(ranked);
  shots_.insert(shots_.end(), std::make_move_iterator(rest.begin()), std::make_move_iterator(rest.end()));
  int blocks = (request_.monte_carlo_samples + kBlock - 1) / kBlock;
  if (n > 0) blocks = std::min(blocks, static_cast<int>(schedule_.monte_carlo_simulations / (n * kBlock)));
  blocks = std::max(blocks, request_.monte_carlo_samples > 0 ? 1 : 0);
  if (n == 0 || blocks == 0 || cut_.Ended(schedule_.monte_carlo)) return;
  AddWorkers(std::min(request_.threads, n * blocks));
  const bool tail_fit = config_.pot_tail_min_samples > 0;
  std::vector<MonteCarloTally> tallies(static_cast<size_t>(n * blocks));
  ParallelFor(request_.threads, n * blocks, [&](int task, int worker) {
    const int s = task / blocks, b = task % blocks;
    const PlannedShot& ps = shots_[static_cast<size_t>(s)];
    // Streams keyed by the shot itself (kind, object, pocket) and the block, so a
    // shot's samples do not depend on the other shots ranked with it.
    const std::uint64_t key = (static_cast<std::uint64_t>(ps.kind) * 64 + static_cast<std::uint64_t>(ps.object_ball + 1)) * 8 +
                              static_cast<std::uint64_t>(ps.pocket);
    Worker& w = *workers_[static_cast<size_t>(worker)];
    tallies[static_cast<size_t>(task)] =
        RunSamples(SetupFor(ps), ps.cue, ctx_, settings_, w.full, schedule_.monte_carlo,
                   DeriveSeed(request_.seed, key, static_cast<std::uint64_t>(b)), kBlock,
                   tail_fit && ps.kind == ShotKind::kPot && ps.route == PotRoute::kDirect, &w.samples);
  });
  cut_.Ended(schedule_.monte_carlo);
  for (int s = 0; s < n; ++s) {
    MonteCarloTally t;
    for (int b = 0; b < blocks; ++b) t.Add(tallies[static_cast<size_t>(s * blocks + b)]);
    answer_.simulations += t.samples;
    answer_.deadline_hit = answer_.deadline_hit || t.interrupted;
    PlannedShot& ps = shots_[static_cast<size_t>(s)];
    if (t.samples == 0) continue;
    ps.monte_carlo_samples = t.samples;
    if (ps.kind == ShotKind::kPot) {
      ps.pot_probability = t.success_rate();
      ps.pocket_probability = t.pocket_rate();
    }
    ps.foul_probability = t.foul_rate();
    ps.handovers.runs = t.handovers;
    ps.handovers.snookered_runs = t.handovers_snookered;
    if (t.handovers > 0) {
      ps.handovers.mean_pot_probability = t.opponent_pot_sum / t.handovers;
      ps.handovers.mean_expected_points = t.opponent_points_sum / t.handovers;
    }
    // Lookahead's correction of the position's estimate, for the pots that succeed.
    const double mean = tail_fit ? t.tail_corrected_score(config_.pot_tail_min_samples) : t.mean_score();
    ps.score = mean + t.success_rate() * ps.lookahead;
  }
  // Shots without samples keep their nominal score, below any sampled competitor in
  // practice. Shots not ranked are not answered: their scores are not comparable.
  std::stable_sort(shots_.begin(), shots_.begin() + n,
                   [](const PlannedShot& a, const PlannedShot& b) { return a.score > b.score; });
  shots_.resize(static_cast<size_t>(n));
}

// The answer's shots, status and reason.
void PlanRun::Conclude() {
  if (static_cast<int>(shots_.size()) > request_.max_shots) shots_.resize(static_cast<size_t>(request_.max_shots));
  answer_.shots = std::move(shots_);
  const bool cancelled = request_.cancel != nullptr && request_.cancel->load();
  if (!answer_.shots.empty()) {
    answer_.status = cancelled ? PlanStatus::kCancelled : PlanStatus::kOk;
    // Why no pot was searched says nothing against a stroke the fallback found that
    // pots a ball after all (it is answered as the pot it is).
    answer_.reason.clear();
    if (cancelled) {
      answer_.reason = "cancelled: the best shots found so far";
    } else if (answer_.shots.front().kind == ShotKind::kFoul) {
      answer_.reason = (no_candidates_.empty() ? std::string("no shot found") : no_candidates_) +
                       "; no legal stroke was found, so the shot is the foul that costs least";
    }
    if (fallback_past_budget_ && !cancelled) {
      answer_.reason += std::string(answer_.reason.empty() ? "" : "; ") +
                        "the time budget ran out before the search verified a shot: the fallback's stroke, "
                        "verified after it";
    }
  } else if (cancelled) {
    answer_.status = PlanStatus::kCancelled;
    answer_.reason = "cancelled before any shot was verified";
  } else if (answer_.deadline_hit && answer_.verified == 0) {
    const bool deadline = schedule_.deadline_binds && Clock::now() >= request_.deadline;
    answer_.status = deadline ? PlanStatus::kDeadline : PlanStatus::kBudgetSpent;
    answer_.reason = std::string(deadline ? "the caller's deadline" : "the time budget") +
                     " ran out before any shot was verified (" + std::to_string(answer_.searched) +
                     " candidates started)";
  } else if (!no_candidates_.empty()) {
    answer_.status = PlanStatus::kNoPot;
    answer_.reason = no_candidates_ + FallbackOutcome();
  } else {
    answer_.status = PlanStatus::kNoPot;
    answer_.reason = "no shot found: the search of " + std::to_string(answer_.searched) + " of " +
                     std::to_string(answer_.candidates) +
                     " candidates found none that does what it is for without a foul";
    if (answer_.verification_failures > 0) {
      answer_.reason += " (" + std::to_string(answer_.verification_failures) + " failed the full-fidelity check)";
    }
    answer_.reason += FallbackOutcome();
  }
}

// What the fallback's scan adds to the reason of an answer without shots: nothing
// when it did not run (the request took pots only) or ran out of time.
std::string PlanRun::FallbackOutcome() const {
  if (fallback_unasked_) {
    std::string s = std::string(", and the scan's stroke is ") +
                    (*fallback_unasked_ == ShotKind::kEscape ? "an " : "a ") + ToString(*fallback_unasked_) +
                    ", which was not asked for";
    if (*fallback_unasked_ != ShotKind::kFoul && request_.kinds.Has(ShotKind::kFoul)) {
      s += ": a foul is offered only when no legal stroke exists";
    }
    return s;
  }
  return fallback_scanned_ ? ", and no legal stroke was found" : "";
}

}  // namespace

const char* ToString(ShotKind kind) {
  switch (kind) {
    case ShotKind::kPot: return "POT";
    case ShotKind::kSafety: return "SAFETY";
    case ShotKind::kEscape: return "ESCAPE";
    case ShotKind::kBreakOff: return "BREAK_OFF";
    case ShotKind::kFoul: return "FOUL";
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

PlannerConfig PlannerConfig::WithModel(const physics::Model& m) const {
  PlannerConfig c = *this;
  c.full = m.Apply(full);
  c.search = m.Apply(search);
  c.cue = m.cue;
  return c;
}

Planner::Planner(const Config& config) : config_(config) {
  // The shared pocket and throw models hold for the default table and the default
  // physics (the cue plays no part in them).
  physics::Model physics_only = config_.model();
  physics_only.cue = physics::CueParams{};
  if (config_.table == &physics::DefaultTable() && physics::SameModel(physics_only, physics::Model{})) {
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
  // The estimates take the cue's noise as it acts on the cue ball: at a typical
  // mid-table speed of 1.5 m/s for the spin of a misplaced tip.
  ctx.execution = request.noise;
  ctx.noise = BallTermsNoise(request.noise, config_.cue, config_.full.ball, 1.5);
  ctx.cue_model = &config_.cue;
  ctx.position_sigma = request.position_sigma;
  ctx.cue = request.limits.cue;
  return ctx;
}

PlanAnswer Planner::Plan(const PlanRequest& request) const { return PlanRun(*this, request).Run(); }

}  // namespace snooker::planner
