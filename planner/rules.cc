#include "planner/rules.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace snooker::planner {
namespace {

// A re-spotted ball is "touching" another when their centres are closer than 2R
// plus this margin (m): a spot with a ball exactly 2R away is occupied (the rule's
// "touch"), and placement keeps this much air between balls.
constexpr double kSpotClearance = 1e-6;

constexpr BallKind kColoursHighFirst[] = {BallKind::kBlack, BallKind::kPink, BallKind::kBlue,
                                          BallKind::kBrown, BallKind::kGreen, BallKind::kYellow};

bool Free(const physics::Vec2& p, std::span<const physics::Vec2> others, double radius) {
  for (const physics::Vec2& o : others) {
    if ((p - o).norm() < 2 * radius + kSpotClearance) return false;
  }
  return true;
}

// The first free position on the vertical line x = p.x from p.y in direction `dir`
// (+1: towards the top cushion, -1: towards baulk), or nullopt before `limit`. Each
// ball blocks one interval of y; step past the interval containing y until free.
std::optional<physics::Vec2> FirstFreeOnLine(const physics::Vec2& p, double dir, double limit,
                                             std::span<const physics::Vec2> others, double radius) {
  const double reach = 2 * radius + kSpotClearance;
  double y = p.y();
  for (size_t guard = 0; guard <= others.size(); ++guard) {  // each step passes one ball
    bool moved = false;
    for (const physics::Vec2& o : others) {
      const double dx = std::abs(o.x() - p.x());
      if (dx >= reach) continue;
      const double half = std::sqrt(reach * reach - dx * dx);
      if (std::abs(y - o.y()) < half) {
        const double past = o.y() + dir * half;
        if (dir * (past - y) > 1e-12) {  // a strict step: y only ever moves on
          y = past;
          moved = true;
        }
      }
    }
    if (dir * (y - limit) > 0) return std::nullopt;
    if (!moved) return physics::Vec2(p.x(), y);
  }
  return std::nullopt;
}

}  // namespace

const char* ToString(BallKind k) {
  switch (k) {
    case BallKind::kCue: return "cue";
    case BallKind::kRed: return "red";
    case BallKind::kYellow: return "yellow";
    case BallKind::kGreen: return "green";
    case BallKind::kBrown: return "brown";
    case BallKind::kBlue: return "blue";
    case BallKind::kPink: return "pink";
    case BallKind::kBlack: return "black";
  }
  return "unknown";
}

int Value(BallKind k) {
  switch (k) {
    case BallKind::kCue: return 0;
    case BallKind::kRed: return 1;
    case BallKind::kYellow: return 2;
    case BallKind::kGreen: return 3;
    case BallKind::kBrown: return 4;
    case BallKind::kBlue: return 5;
    case BallKind::kPink: return 6;
    case BallKind::kBlack: return 7;
  }
  return 0;
}

bool IsColour(BallKind k) { return k != BallKind::kCue && k != BallKind::kRed; }

physics::Colour ColourOf(BallKind k) {
  return static_cast<physics::Colour>(static_cast<int>(k) - static_cast<int>(BallKind::kYellow));
}

BallKind KindOf(physics::Colour c) {
  return static_cast<BallKind>(static_cast<int>(c) + static_cast<int>(BallKind::kYellow));
}

const char* ToString(BallOn on) {
  switch (on) {
    case BallOn::kRed: return "red";
    case BallOn::kAnyColour: return "colour";
    case BallOn::kYellow: return "yellow";
    case BallOn::kGreen: return "green";
    case BallOn::kBrown: return "brown";
    case BallOn::kBlue: return "blue";
    case BallOn::kPink: return "pink";
    case BallOn::kBlack: return "black";
  }
  return "unknown";
}

BallOn BallOnFor(BallKind colour) {
  return static_cast<BallOn>(static_cast<int>(colour) - static_cast<int>(BallKind::kYellow) +
                             static_cast<int>(BallOn::kYellow));
}

int TableState::cue_index() const {
  for (size_t i = 0; i < balls.size(); ++i) {
    if (balls[i].kind == BallKind::kCue) return static_cast<int>(i);
  }
  return -1;
}

int TableState::Count(BallKind k) const {
  return static_cast<int>(std::count_if(balls.begin(), balls.end(),
                                        [k](const Ball& b) { return b.kind == k; }));
}

bool IsLegalTarget(BallOn on, BallKind kind) {
  switch (on) {
    case BallOn::kRed: return kind == BallKind::kRed;
    case BallOn::kAnyColour: return IsColour(kind);
    default: return IsColour(kind) && BallOnFor(kind) == on;
  }
}

std::optional<BallOn> OpeningBallOn(const TableState& table) {
  if (table.reds() > 0) return BallOn::kRed;
  for (int c = 0; c < physics::kColourCount; ++c) {
    const BallKind k = KindOf(static_cast<physics::Colour>(c));
    if (table.Count(k) > 0) return BallOnFor(k);
  }
  return std::nullopt;
}

const char* ToString(Foul f) {
  switch (f) {
    case Foul::kNone: return "none";
    case Foul::kNoBallHit: return "no ball hit";
    case Foul::kWrongBallFirst: return "wrong ball hit first";
    case Foul::kCuePotted: return "cue ball potted";
    case Foul::kWrongBallPotted: return "ball not on potted";
    case Foul::kSimulationFailed: return "simulation failed";
  }
  return "unknown";
}

std::vector<int> TouchingCueBall(const TableState& table, const physics::TableModel& model) {
  std::vector<int> touching;
  const int cue = table.cue_index();
  if (cue < 0) return touching;
  const physics::Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const double reach = 2 * model.ball_radius() + kTouchingGap;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (static_cast<int>(i) != cue && (table.balls[i].position - c).norm() <= reach) {
      touching.push_back(static_cast<int>(i));
    }
  }
  return touching;
}

namespace {

// With any colour on, the nominated colour is the ball on for this shot.
BallOn EffectiveBallOn(BallOn on, std::optional<BallKind> nominated) {
  return on == BallOn::kAnyColour && nominated && IsColour(*nominated) ? BallOnFor(*nominated) : on;
}

// The value of the ball on: a red 1, a colour its value, any colour (none
// nominated) 0 (the first ball hit then counts).
int BallOnValue(BallOn on) {
  switch (on) {
    case BallOn::kRed: return Value(BallKind::kRed);
    case BallOn::kAnyColour: return 0;
    default: return static_cast<int>(on) - static_cast<int>(BallOn::kYellow) + Value(BallKind::kYellow);
  }
}

}  // namespace

int FoulPenalty(const TableState& table, BallOn on, std::optional<BallKind> nominated, int first_hit,
                std::span<const int> potted) {
  constexpr int kMinimumPenalty = 4;
  const int n = static_cast<int>(table.balls.size());
  int penalty = std::max(kMinimumPenalty, BallOnValue(EffectiveBallOn(on, nominated)));
  if (first_hit >= 0 && first_hit < n) {
    penalty = std::max(penalty, Value(table.balls[static_cast<size_t>(first_hit)].kind));
  }
  for (const int i : potted) {
    if (i >= 0 && i < n) penalty = std::max(penalty, Value(table.balls[static_cast<size_t>(i)].kind));
  }
  return penalty;
}

ShotJudgement JudgeShot(const TableState& table, BallOn on, std::optional<BallKind> nominated,
                        int first_hit, std::span<const int> potted, std::span<const int> touching) {
  ShotJudgement j;
  const BallOn effective = EffectiveBallOn(on, nominated);
  const int n = static_cast<int>(table.balls.size());
  auto is_on = [&](int i) {
    return i >= 0 && i < n && IsLegalTarget(effective, table.balls[static_cast<size_t>(i)].kind);
  };
  // A touching ball on counts as hit: playing away from it is a fair first contact.
  const bool touching_on = std::any_of(touching.begin(), touching.end(), is_on);
  if (!touching_on) {
    if (first_hit < 0 || first_hit >= n) {
      j.foul = Foul::kNoBallHit;
    } else if (!is_on(first_hit)) {
      j.foul = Foul::kWrongBallFirst;
    }
  }
  for (const int i : potted) {
    if (i < 0 || i >= n) continue;
    const BallKind k = table.balls[static_cast<size_t>(i)].kind;
    if (k == BallKind::kCue) {
      j.foul = Foul::kCuePotted;
    } else if (!IsLegalTarget(effective, k) && j.foul == Foul::kNone) {
      j.foul = Foul::kWrongBallPotted;
    }
  }
  if (j.foul != Foul::kNone) {
    j.penalty = FoulPenalty(table, on, nominated, first_hit, potted);
    return j;
  }
  for (const int i : potted) {
    if (i < 0 || i >= n) continue;
    const BallKind k = table.balls[static_cast<size_t>(i)].kind;
    ++j.legal_pots;
    j.points += Value(k);
    j.potted_kind = k;
  }
  return j;
}

std::optional<BallOn> NextBallOn(BallOn on, BallKind potted_kind, const TableState& after) {
  if (on == BallOn::kRed && potted_kind == BallKind::kRed) return BallOn::kAnyColour;
  // After a colour: a red while reds remain, else the lowest colour left.
  return OpeningBallOn(after);
}

std::optional<physics::Vec2> RespotPosition(BallKind colour, std::span<const physics::Vec2> others,
                                            const physics::TableModel& table) {
  const double r = table.ball_radius();
  const physics::Vec2 own = table.spot(ColourOf(colour));
  if (Free(own, others, r)) return own;
  for (const BallKind k : kColoursHighFirst) {
    const physics::Vec2 spot = table.spot(ColourOf(k));
    if (Free(spot, others, r)) return spot;
  }
  const double c = table.cushion_contact_distance();
  const double top = table.spec().length - c;
  if (auto p = FirstFreeOnLine(own, +1, top, others, r)) return p;
  return FirstFreeOnLine(own, -1, c, others, r);
}

TableState ApplyShot(const TableState& before, BallOn on, std::span<const physics::Vec2> final_positions,
                     std::span<const int> potted, bool foul, const physics::TableModel& table,
                     std::vector<int>* origin) {
  TableState after;
  after.balls.reserve(before.balls.size());
  ApplyShotInto(before, on, final_positions, potted, foul, table, &after, origin);
  return after;
}

void ApplyShotInto(const TableState& before, BallOn on, std::span<const physics::Vec2> final_positions,
                   std::span<const int> potted, bool foul, const physics::TableModel& table, TableState* after,
                   std::vector<int>* origin) {
  const size_t n = before.balls.size();
  auto down = [&](size_t i) { return std::find(potted.begin(), potted.end(), static_cast<int>(i)) != potted.end(); };
  after->balls.clear();
  if (origin != nullptr) origin->clear();
  auto add = [&](BallKind k, const physics::Vec2& p, size_t from) {
    after->balls.push_back({k, p});
    if (origin != nullptr) origin->push_back(static_cast<int>(from));
  };
  for (size_t i = 0; i < n; ++i) {
    if (!down(i)) add(before.balls[i].kind, final_positions[i], i);
  }
  // Potted colours come back highest value first, unless one stays down: the ball
  // on in the final sequence, potted fairly. The colour after the last red
  // (kAnyColour) comes back; reds stay down; a potted cue ball is in hand.
  const bool reds_before = before.reds() > 0;
  constexpr BallKind kByValue[] = {BallKind::kBlack, BallKind::kPink,  BallKind::kBlue,
                                   BallKind::kBrown, BallKind::kGreen, BallKind::kYellow};
  std::array<physics::Vec2, physics::limits::kMaxBalls> buffer;
  std::vector<physics::Vec2> spill;  // tables past the limit only (not validated ones)
  for (const BallKind k : kByValue) {
    const bool stays_down = !foul && !reds_before && on != BallOn::kAnyColour && IsLegalTarget(on, k);
    if (stays_down) continue;
    for (size_t i = 0; i < n; ++i) {
      if (before.balls[i].kind != k || !down(i)) continue;
      const size_t m = after->balls.size();
      std::span<physics::Vec2> others;
      if (m <= buffer.size()) {
        others = std::span<physics::Vec2>(buffer.data(), m);
      } else {
        spill.resize(m);
        others = spill;
      }
      for (size_t j = 0; j < m; ++j) others[j] = after->balls[j].position;
      if (const auto p = RespotPosition(k, others, table)) add(k, *p, i);
    }
  }
}

}  // namespace snooker::planner
