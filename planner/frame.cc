#include "planner/frame.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "planner/random.h"

namespace snooker::planner {

using physics::Vec2;

namespace {

// Placement tolerance of the D's lines and of touching balls, m (rounding only).
constexpr double kPlacementSlack = 1e-9;

std::string Describe(const Vec2& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ") m";
  return s.str();
}

std::string IndexError(const char* what, int i, size_t n) {
  std::ostringstream s;
  s << what << " " << i << " is not a ball of the stroke's table (0 to " << n - 1 << ")";
  return s.str();
}

// The other player.
int Opponent(int player) { return 1 - player; }

// Ends the frame: the higher score wins; on equal scores the black goes back on its
// spot (the only ball), the cue ball in hand, and the seed picks the striker.
void EndFrame(FrameState& f, FrameEnd end, const physics::TableModel& model) {
  if (f.score[0] != f.score[1]) {
    f.over = true;
    f.end = end;
    f.winner = f.score[0] > f.score[1] ? 0 : 1;
    return;
  }
  f.table.balls = {Ball{BallKind::kBlack, model.spot(physics::Colour::kBlack)}};
  f.ball_on = BallOn::kBlack;
  f.cue_in_hand = true;
  f.black_respotted = true;
  Rng coin(DeriveSeed(f.seed, static_cast<std::uint64_t>(f.shots)));
  f.striker = static_cast<int>(coin.Next() & 1u);
}

// The nomination the judgement uses: the stroke's, else the first ball hit when a
// colour is on and it is a colour.
std::optional<BallKind> Nomination(const FrameState& f, const Stroke& s, const TableState& t) {
  if (f.ball_on != BallOn::kAnyColour) return std::nullopt;
  if (s.nominated) return s.nominated;
  const bool hit = s.first_hit >= 0 && s.first_hit < static_cast<int>(t.balls.size());
  if (hit && IsColour(t.balls[static_cast<size_t>(s.first_hit)].kind)) {
    return t.balls[static_cast<size_t>(s.first_hit)].kind;
  }
  return std::nullopt;
}

}  // namespace

const char* ToString(FrameEnd end) {
  switch (end) {
    case FrameEnd::kPlaying: return "playing";
    case FrameEnd::kBlackPotted: return "black potted";
    case FrameEnd::kBlackFouled: return "black fouled";
    case FrameEnd::kShotCap: return "shot cap";
  }
  return "unknown";
}

FrameState StartFrame(std::uint64_t seed, int breaker, const physics::TableModel& model) {
  if (breaker != 0 && breaker != 1) {
    throw std::invalid_argument("breaker " + std::to_string(breaker) + " is not a player (0 or 1)");
  }
  FrameState f;
  f.seed = seed;
  f.striker = breaker;
  for (const Vec2& r : model.reds()) f.table.balls.push_back({BallKind::kRed, r});
  for (int c = 0; c < physics::kColourCount; ++c) {
    const auto colour = static_cast<physics::Colour>(c);
    f.table.balls.push_back({KindOf(colour), model.spot(colour)});
  }
  return f;
}

bool InTheD(const Vec2& p, const physics::TableModel& model) {
  const physics::TableSpec& spec = model.spec();
  const Vec2 centre(spec.width / 2, spec.baulk_line);
  return p.y() <= spec.baulk_line + kPlacementSlack && (p - centre).norm() <= spec.d_radius + kPlacementSlack;
}

std::string CuePlacementError(const TableState& table, const Vec2& p, const physics::TableModel& model) {
  if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return "cue ball placement " + Describe(p) + " is not finite";
  if (!InTheD(p, model)) return "cue ball placement " + Describe(p) + " is not in the D";
  const double two_r = 2 * model.ball_radius() - kPlacementSlack;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const Ball& b = table.balls[i];
    if (b.kind == BallKind::kCue) return "cue ball placement: the table already holds a cue ball";
    if ((b.position - p).norm() < two_r) {
      return "cue ball placement " + Describe(p) + " overlaps the " + ToString(b.kind) + " (ball " +
             std::to_string(i) + ") at " + Describe(b.position);
    }
  }
  return "";
}

TableState StrokeTable(const FrameState& frame, const std::optional<Vec2>& cue_start) {
  TableState t = frame.table;
  if (frame.cue_in_hand && cue_start) t.balls.push_back({BallKind::kCue, *cue_start});
  return t;
}

std::string StrokeError(const FrameState& f, const Stroke& s, const physics::TableModel& model) {
  if (f.over) return std::string("the frame is over (") + ToString(f.end) + ")";
  if (f.cue_in_hand) {
    if (!s.cue_start) return "the cue ball is in hand: the stroke needs its cue_start";
    if (std::string e = CuePlacementError(f.table, *s.cue_start, model); !e.empty()) return e;
  }
  const TableState t = StrokeTable(f, s.cue_start);
  const size_t n = t.balls.size();
  if (t.cue_index() < 0) return "the table holds no cue ball and it is not in hand";
  if (!s.simulation_failed) {
    if (s.ends.size() != n) {
      return "ends has " + std::to_string(s.ends.size()) + " positions for " + std::to_string(n) + " balls";
    }
    if (s.first_hit < -1 || s.first_hit >= static_cast<int>(n)) return IndexError("first_hit", s.first_hit, n);
    for (const int i : s.potted) {
      if (i < 0 || i >= static_cast<int>(n)) return IndexError("potted ball", i, n);
    }
  }
  for (const int i : s.touching) {
    if (i < 0 || i >= static_cast<int>(n)) return IndexError("touching ball", i, n);
  }
  if (s.nominated && !IsColour(*s.nominated)) {
    return std::string("nominated ball ") + ToString(*s.nominated) + " is not a colour";
  }
  return "";
}

StrokeResult ApplyStroke(FrameState& f, const Stroke& s, const physics::TableModel& model) {
  if (std::string e = StrokeError(f, s, model); !e.empty()) throw std::invalid_argument(e);
  const TableState before = StrokeTable(f, s.cue_start);
  const BallOn on = f.ball_on;
  StrokeResult r;
  r.striker = f.striker;
  const std::optional<BallKind> nominated = Nomination(f, s, before);
  std::vector<Vec2> ends = s.ends;
  std::vector<int> potted = s.potted;
  if (s.simulation_failed) {
    r.judgement.foul = Foul::kSimulationFailed;
    r.judgement.penalty = FoulPenalty(before, on, nominated, -1, {});
    ends.clear();
    for (const Ball& b : before.balls) ends.push_back(b.position);
    potted.clear();
  } else {
    r.judgement = JudgeShot(before, on, nominated, s.first_hit, potted, s.touching);
  }
  const bool foul = r.judgement.foul != Foul::kNone;
  f.table = ApplyShot(before, on, ends, potted, foul, model);
  f.cue_in_hand = f.table.cue_index() < 0;
  ++f.shots;
  std::optional<BallOn> next;
  if (foul) {
    f.score[static_cast<size_t>(Opponent(f.striker))] += r.judgement.penalty;
  } else {
    f.score[static_cast<size_t>(f.striker)] += r.judgement.points;
    f.visit_points += r.judgement.points;
    if (r.judgement.legal_pots > 0) next = NextBallOn(on, *r.judgement.potted_kind, f.table);
  }
  const bool continues = !foul && r.judgement.legal_pots > 0;
  const bool black_potted = continues && !next;
  const bool black_fouled = foul && on == BallOn::kBlack;
  r.visit_over = !continues || black_potted || black_fouled || f.shots >= f.max_shots;
  if (r.visit_over) {
    r.break_points = f.visit_points;
    f.visit_points = 0;
  }
  if (continues && next) {
    f.ball_on = *next;
  } else if (!black_potted && !black_fouled) {
    f.striker = Opponent(f.striker);
    f.ball_on = OpeningBallOn(f.table).value_or(BallOn::kBlack);
  }
  if (black_potted || black_fouled) {
    EndFrame(f, black_potted ? FrameEnd::kBlackPotted : FrameEnd::kBlackFouled, model);
  }
  if (!f.over && f.shots >= f.max_shots) {
    f.over = true;
    f.end = FrameEnd::kShotCap;
    f.winner = f.score[0] == f.score[1] ? -1 : (f.score[0] > f.score[1] ? 0 : 1);
  }
  return r;
}

}  // namespace snooker::planner
