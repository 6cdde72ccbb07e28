// Tests of the match (planner/match.h): the players by name and what they ask the
// planner for, the fallback stroke of a stall, bad options named, and a short match
// that is consistent and a function of its seed.
#include "planner/match.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "planner/geometry.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

const physics::TableModel& Table() { return physics::DefaultTable(); }
double R() { return Table().ball_radius(); }

TEST(MatchTest, PlayersByName) {
  for (int k = 0; k < kPlayerKindCount; ++k) {
    const auto kind = static_cast<PlayerKind>(k);
    EXPECT_EQ(ParsePlayerKind(ToString(kind)), kind);
  }
  EXPECT_EQ(ParsePlayerKind("Default"), std::nullopt);
  EXPECT_EQ(ParsePlayerKind(""), std::nullopt);
}

TEST(MatchTest, EachPlayerAsksThePlannerForItsOwnShots) {
  PlanRequest r;
  ConfigureRequest(PlayerKind::kDirectPots, &r);
  EXPECT_EQ(r.kinds, ShotKinds::Of(ShotKind::kPot));
  EXPECT_EQ(r.routes, PotRoutes::Of(PotRoute::kDirect));
  EXPECT_FALSE(r.lookahead);
  EXPECT_FALSE(r.break_value.has_value());  // the planner's own
  ConfigureRequest(PlayerKind::kOnePly, &r);
  EXPECT_EQ(r.kinds, ShotKinds{});
  EXPECT_EQ(r.routes, PotRoutes{});
  EXPECT_FALSE(r.lookahead);
  EXPECT_EQ(r.break_value, kFrameBreakValue);
  EXPECT_FALSE(r.position_spread.has_value());  // 0: the planner's own
  ConfigureRequest(PlayerKind::kDefault, &r, 55, 2);
  EXPECT_TRUE(r.kinds.Has(ShotKind::kSafety));
  EXPECT_TRUE(r.routes.Has(PotRoute::kPlant));
  EXPECT_TRUE(r.lookahead);
  EXPECT_EQ(r.break_value, 55);
  EXPECT_EQ(r.position_spread, 2);
  ConfigureRequest(PlayerKind::kDirectPots, &r, 55, 2);
  EXPECT_FALSE(r.break_value.has_value());
  EXPECT_FALSE(r.position_spread.has_value());
}

TEST(MatchTest, BadOptionsAreNamed) {
  MatchOptions o;
  EXPECT_EQ(MatchOptionsError(o), "");
  o.frames = 0;
  o.max_shots_per_frame = 201;
  o.time_budget = -1;
  o.break_value = 200;
  o.position_spread = 5;
  const std::string e = MatchOptionsError(o);
  EXPECT_NE(e.find("break_value = 200 (must be in [0, 147] points)"), std::string::npos) << e;
  EXPECT_NE(e.find("position_spread = 5 (must be in [0, 4])"), std::string::npos) << e;
  EXPECT_NE(e.find("frames = 0"), std::string::npos) << e;
  EXPECT_NE(e.find("max_shots_per_frame = 201"), std::string::npos) << e;
  EXPECT_NE(e.find("time_budget"), std::string::npos) << e;
  EXPECT_THROW(RunMatch(Planner::Default(), o), std::invalid_argument);
}

TEST(FallbackTest, AimsAtTheNearestBallOnWithAClearPath) {
  // Red 1 is nearest but the black stands in the way; red 2 is clear. Then the
  // yellow stands in red 2's way too.
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(0.9, 1.0)},
             {BallKind::kRed, Vec2(0.9, 1.3)},
             {BallKind::kBlack, Vec2(0.9, 1.15)},
             {BallKind::kRed, Vec2(1.3, 1.1)}};
  RobotLimits limits;
  FallbackShot s = NearestBallOnShot(t, false, BallOn::kRed, limits, Table());
  EXPECT_EQ(s.target, 3);
  EXPECT_EQ(s.first_ball, 3);
  EXPECT_TRUE(s.clear);
  EXPECT_FALSE(s.cue_start);
  EXPECT_NEAR(s.shot.heading, Direction(Vec2(0.4, 0.1)), 1e-12);
  EXPECT_EQ(s.shot.speed, kFallbackSpeed);
  EXPECT_EQ(s.shot.topspin, 0);
  EXPECT_EQ(s.shot.sidespin, 0);
  // Red 2 blocked too (by a yellow): the nearest red, though not clear.
  t.balls.push_back({BallKind::kYellow, Vec2(1.1, 1.05)});
  s = NearestBallOnShot(t, false, BallOn::kRed, limits, Table());
  EXPECT_EQ(s.target, 1);
  EXPECT_EQ(s.first_ball, 2);  // the black
  EXPECT_FALSE(s.clear);
  // The robot's speed limits hold.
  limits.max_speed = 1.0;
  EXPECT_EQ(NearestBallOnShot(t, false, BallOn::kRed, limits, Table()).shot.speed, 1.0);
}

TEST(FallbackTest, WithTheCueBallInHandItPlacesItInTheD) {
  const FrameState f = StartFrame(1, 0);
  const FallbackShot s = NearestBallOnShot(f.table, true, BallOn::kRed, RobotLimits{}, Table());
  ASSERT_TRUE(s.cue_start);
  EXPECT_EQ(CuePlacementError(f.table, *s.cue_start, Table()), "");
  ASSERT_GE(s.target, 0);
  ASSERT_LT(s.target, static_cast<int>(f.table.balls.size()));
  EXPECT_EQ(f.table.balls[static_cast<size_t>(s.target)].kind, BallKind::kRed);
  // From the D no red of the triangle is free of its neighbours, but a red in front
  // of the one aimed at is met first: the shot is a fair hit.
  EXPECT_TRUE(s.clear);
  EXPECT_NE(s.first_ball, s.target);
  ASSERT_GE(s.first_ball, 0);
  ASSERT_LT(s.first_ball, static_cast<int>(f.table.balls.size()));
  EXPECT_EQ(f.table.balls[static_cast<size_t>(s.first_ball)].kind, BallKind::kRed);
  // The shot goes from the placement at the target.
  const Vec2 to = f.table.balls[static_cast<size_t>(s.target)].position - *s.cue_start;
  EXPECT_NEAR(s.shot.heading, Direction(to), 1e-12);
}

TEST(FallbackTest, PlaysAwayFromATouchingBallOn) {
  // Only the black is on, and it touches the cue ball.
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(0.9, 2.0)}, {BallKind::kBlack, Vec2(0.9, 2.0 + 2 * R())}};
  const FallbackShot s = NearestBallOnShot(t, false, BallOn::kBlack, RobotLimits{}, Table());
  EXPECT_EQ(s.target, -1);
  EXPECT_NEAR(s.shot.heading, -physics::kPi / 2, 1e-12);
}

MatchOptions ShortMatch() {
  MatchOptions o;
  o.frames = 2;
  o.seed = 7;
  o.players = {PlayerKind::kDefault, PlayerKind::kDirectPots};
  o.time_budget = 30;  // the simulation cap, not the clock, ends each plan
  o.max_simulations = 60;
  o.monte_carlo_samples = 8;
  o.max_shots_per_frame = 10;
  return o;
}

TEST(MatchTest, AShortMatchIsConsistent) {
  MatchOptions o = ShortMatch();
  int outlooks = 0;
  o.outlook = [&outlooks](const TableState&, bool, BallOn) {
    ++outlooks;
    return 0.25;
  };
  std::vector<StrokeRecord> log;
  o.on_stroke = [&log](const StrokeRecord& s) { log.push_back(s); };
  int frames_seen = 0;
  const MatchReport r = RunMatch(Planner::Default(), o, [&](int frame, const FrameSummary&) {
    EXPECT_EQ(frame, frames_seen);
    ++frames_seen;
  });
  EXPECT_EQ(frames_seen, 2);
  ASSERT_EQ(r.frames, 2);
  ASSERT_EQ(r.records.size(), 2u);
  EXPECT_EQ(r.records[0].breaker, 0);
  EXPECT_EQ(r.records[1].breaker, 1);
  int shots = 0, stalls = 0, points_a = 0, points_b = 0, decided = 0;
  for (const FrameSummary& f : r.records) {
    EXPECT_GT(f.shots, 0);
    EXPECT_LE(f.shots, o.max_shots_per_frame);
    EXPECT_NE(f.end, FrameEnd::kPlaying);
    shots += f.shots;
    stalls += f.stalls;
    points_a += f.score[0];
    points_b += f.score[1];
    if (f.winner >= 0) {
      ++decided;
      EXPECT_GT(f.score[static_cast<size_t>(f.winner)], f.score[static_cast<size_t>(1 - f.winner)]);
    }
  }
  EXPECT_EQ(r.shots, shots);
  EXPECT_EQ(r.stalls, stalls);
  EXPECT_EQ(r.players[0].shots + r.players[1].shots, shots);
  EXPECT_EQ(r.players[0].stalls + r.players[1].stalls, stalls);
  EXPECT_EQ(r.players[0].points, points_a);
  EXPECT_EQ(r.players[1].points, points_b);
  EXPECT_EQ(r.players[0].frames_won + r.players[1].frames_won, decided);
  EXPECT_EQ(decided + r.frames_undecided, 2);
  EXPECT_LE(r.frames_undecided, r.frames_capped);
  for (const PlayerStats& p : r.players) {
    EXPECT_EQ(static_cast<int>(p.plan_ms.size()), p.shots);
    EXPECT_LE(p.plan_ms_p50, p.plan_ms_p99);
    EXPECT_LE(p.penalty_points, p.points);
    // A player's points are its breaks and the opponent's penalties.
    EXPECT_EQ(std::accumulate(p.breaks.begin(), p.breaks.end(), 0) + p.penalty_points, p.points);
    EXPECT_LE(static_cast<int>(p.safety_outlook.size()), p.safeties);
    for (const double v : p.safety_outlook) EXPECT_EQ(v, 0.25);
    // One break-off each in two frames, measured when it handed the table over.
    EXPECT_LE(p.break_off_outlook.size(), 1u);
    for (const double v : p.break_off_outlook) EXPECT_EQ(v, 0.25);
  }
  EXPECT_EQ(r.players[0].kind, PlayerKind::kDefault);
  EXPECT_EQ(r.players[1].kind, PlayerKind::kDirectPots);
  // The outlook is asked once per handover (the next stroke of the frame is the
  // other player's), logged with that stroke, and the safeties' and break-offs'
  // figures are those strokes' values.
  int handovers = 0;
  for (size_t k = 0; k < log.size(); ++k) {
    const bool handed_over = k + 1 < log.size() && log[k + 1].frame == log[k].frame &&
                             log[k + 1].striker != log[k].striker;
    EXPECT_EQ(std::isfinite(log[k].handover_outlook), handed_over) << "stroke " << k;
    if (!handed_over) continue;
    ++handovers;
    EXPECT_EQ(log[k].handover_outlook, 0.25);
  }
  EXPECT_GT(handovers, 0);
  EXPECT_EQ(outlooks, handovers);
  EXPECT_LE(r.players[0].safety_outlook.size() + r.players[1].safety_outlook.size() +
                r.players[0].break_off_outlook.size() + r.players[1].break_off_outlook.size(),
            static_cast<size_t>(handovers));
  // Each frame's break-off hands the table over unless it pots a red.
  EXPECT_GE(r.players[0].break_off_outlook.size() + r.players[1].break_off_outlook.size(), 1u);
}

// The stroke log (MatchOptions::on_stroke) replays the match: one record per stroke
// in order, and its points and penalties add up to each frame's score.
TEST(MatchTest, TheStrokeLogAddsUpToTheFrames) {
  MatchOptions o = ShortMatch();
  std::vector<StrokeRecord> log;
  o.on_stroke = [&log](const StrokeRecord& s) { log.push_back(s); };
  const MatchReport r = RunMatch(Planner::Default(), o);
  ASSERT_EQ(static_cast<int>(log.size()), r.shots);
  size_t k = 0;
  int safeties = 0, stalls = 0;
  for (int frame = 0; frame < r.frames; ++frame) {
    const FrameSummary& f = r.records[static_cast<size_t>(frame)];
    std::array<int, 2> score{0, 0};
    for (int stroke = 1; stroke <= f.shots; ++stroke, ++k) {
      const StrokeRecord& s = log[k];
      EXPECT_EQ(s.frame, frame);
      EXPECT_EQ(s.stroke, stroke);
      EXPECT_EQ(s.turn == TurnType::kBreakOff, stroke == 1);
      if (stroke == 1) {
        EXPECT_EQ(s.striker, f.breaker);
      }
      score[static_cast<size_t>(s.striker)] += s.points;
      score[static_cast<size_t>(1 - s.striker)] += s.penalty;
      EXPECT_EQ(s.score, score) << "frame " << frame << " stroke " << stroke;
      EXPECT_EQ(s.foul == Foul::kNone, s.penalty == 0);
      if (s.foul != Foul::kNone) {
        EXPECT_EQ(s.points, 0);
      }
      // The table the plan was given, with the turn's ball on in it, and no cue
      // ball when it was in hand.
      EXPECT_EQ(s.table.cue_index() < 0, s.turn != TurnType::kOnTable);
      EXPECT_TRUE(std::any_of(s.table.balls.begin(), s.table.balls.end(),
                              [&](const Ball& b) { return IsLegalTarget(s.ball_on, b.kind); }));
      if (s.stall) {
        ++stalls;
        EXPECT_TRUE(std::isnan(s.plan_score));
        EXPECT_FALSE(s.stall_reason.empty());  // why
      } else {
        EXPECT_TRUE(s.stall_reason.empty());
        EXPECT_TRUE(std::isfinite(s.plan_score));
        if (s.kind == ShotKind::kSafety) ++safeties;
      }
      if (!s.stall && s.kind == ShotKind::kPot) {
        EXPECT_GE(s.pot_probability, 0);
        EXPECT_LE(s.pot_probability, 1);
      } else {
        EXPECT_TRUE(std::isnan(s.pot_probability));
      }
    }
    EXPECT_EQ(score, f.score);
  }
  EXPECT_EQ(stalls, r.stalls);
  EXPECT_EQ(safeties, r.players[0].safeties + r.players[1].safeties);
}

// Every turn of the log plans again to the shot it played: the record's table, ball
// on and seed with the match's options are the whole request. Each player's turns
// (the planner configured three ways) and each kind of turn are replayed; a record
// with the wrong seed or a moved ball plans to another answer.
TEST(MatchTest, EveryLoggedTurnPlansAgainToItsShot) {
  std::set<std::pair<PlayerKind, TurnType>> replayed;
  int planned = 0, differs = 0;
  for (const PlayerKind opponent : {PlayerKind::kOnePly, PlayerKind::kDirectPots}) {
    MatchOptions o = ShortMatch();
    o.players = {PlayerKind::kDefault, opponent};
    std::vector<StrokeRecord> log;
    o.on_stroke = [&log](const StrokeRecord& s) { log.push_back(s); };
    (void)RunMatch(Planner::Default(), o);
    for (const StrokeRecord& s : log) {
      if (s.stall) continue;
      const std::string where = "frame " + std::to_string(s.frame) + " stroke " + std::to_string(s.stroke);
      const PlanAnswer again = Planner::Default().Plan(ReplayRequest(o, s));
      ASSERT_FALSE(again.shots.empty()) << where;
      const PlannedShot& p = again.shots.front();
      EXPECT_EQ(p.kind, s.kind) << where;
      EXPECT_EQ(p.route, s.route) << where;
      EXPECT_EQ(p.score, s.plan_score) << where;
      if (s.kind == ShotKind::kPot) {
        EXPECT_EQ(p.pot_probability, s.pot_probability) << where;
      }
      replayed.insert({o.players[static_cast<size_t>(s.striker)], s.turn});
      // The same turn with another seed, or with a ball moved by a millimetre, is
      // another request: the comparison above can fail.
      if (planned++ < 6) {
        StrokeRecord other = s;
        if (planned % 2 == 0) {
          other.table.balls.back().position.x() += 1e-3;
        } else {
          other.plan_seed = s.plan_seed + 1;
        }
        const PlanAnswer moved = Planner::Default().Plan(ReplayRequest(o, other));
        if (moved.shots.empty() || moved.shots.front().score != s.plan_score) ++differs;
      }
    }
  }
  for (const PlayerKind player : {PlayerKind::kDefault, PlayerKind::kOnePly, PlayerKind::kDirectPots}) {
    EXPECT_TRUE(replayed.count({player, TurnType::kOnTable})) << ToString(player);
  }
  EXPECT_TRUE(replayed.count({PlayerKind::kDefault, TurnType::kBreakOff}));
  EXPECT_GT(differs, 0);
}

// A match with the thin break-off asks each player's break-off plan for it, so the
// logged break-off plans again to its score from the record and the options alone;
// the same turn without it is another plan.
TEST(MatchTest, TheThinBreakOffIsInTheReplayedRequest) {
  MatchOptions o = ShortMatch();
  o.frames = 1;
  o.max_shots_per_frame = 1;
  o.thin_break_off = true;
  std::vector<StrokeRecord> log;
  o.on_stroke = [&log](const StrokeRecord& s) { log.push_back(s); };
  (void)RunMatch(Planner::Default(), o);
  ASSERT_EQ(log.size(), 1u);
  const StrokeRecord& s = log.front();
  ASSERT_EQ(s.turn, TurnType::kBreakOff);
  ASSERT_FALSE(s.stall) << s.stall_reason;
  const PlanRequest req = ReplayRequest(o, s);
  EXPECT_EQ(req.thin_break_off, std::optional<bool>(true));
  const PlanAnswer again = Planner::Default().Plan(req);
  ASSERT_FALSE(again.shots.empty()) << again.reason;
  EXPECT_EQ(again.shots.front().score, s.plan_score);
  o.thin_break_off = false;
  const PlanAnswer soft = Planner::Default().Plan(ReplayRequest(o, s));
  EXPECT_LT(soft.searched, again.searched);
}

// The position's spread is the default player's (and one-ply's) setting, not
// direct-pots': each logged turn's replay carries it or not, and plans again to the
// logged stroke.
TEST(MatchTest, ThePositionSpreadIsInTheReplayedRequest) {
  MatchOptions o = ShortMatch();
  o.frames = 1;
  o.position_spread = 2;
  std::vector<StrokeRecord> log;
  o.on_stroke = [&log](const StrokeRecord& s) { log.push_back(s); };
  (void)RunMatch(Planner::Default(), o);
  int defaults = 0;
  for (const StrokeRecord& s : log) {
    if (s.stall) continue;
    const PlanRequest req = ReplayRequest(o, s);
    const bool by_default = o.players[static_cast<size_t>(s.striker)] == PlayerKind::kDefault;
    EXPECT_EQ(req.position_spread, by_default ? std::optional<double>(2) : std::nullopt);
    if (!by_default || defaults++ >= 3) continue;
    const PlanAnswer again = Planner::Default().Plan(req);
    ASSERT_FALSE(again.shots.empty()) << again.reason;
    EXPECT_EQ(again.shots.front().score, s.plan_score);
  }
  EXPECT_GT(defaults, 0);
}

TEST(MatchTest, AMatchIsAFunctionOfItsSeed) {
  const MatchOptions o = ShortMatch();
  const MatchReport a = RunMatch(Planner::Default(), o);
  const MatchReport b = RunMatch(Planner::Default(), o);
  ASSERT_EQ(a.records.size(), b.records.size());
  for (size_t i = 0; i < a.records.size(); ++i) {
    EXPECT_EQ(a.records[i].score, b.records[i].score);
    EXPECT_EQ(a.records[i].shots, b.records[i].shots);
    EXPECT_EQ(a.records[i].stalls, b.records[i].stalls);
    EXPECT_EQ(a.records[i].fouls, b.records[i].fouls);
    EXPECT_EQ(a.records[i].end, b.records[i].end);
  }
  for (size_t p = 0; p < 2; ++p) {
    EXPECT_EQ(a.players[p].breaks, b.players[p].breaks);
    EXPECT_EQ(a.players[p].fouls, b.players[p].fouls);
    EXPECT_EQ(a.players[p].safeties, b.players[p].safeties);
    EXPECT_EQ(a.players[p].penalty_points, b.players[p].penalty_points);
  }
  EXPECT_EQ(a.simulation_failures, b.simulation_failures);
  EXPECT_EQ(a.plans_cut_short, 0);  // every plan ended by its cap
  EXPECT_EQ(b.plans_cut_short, 0);
}

}  // namespace
}  // namespace snooker::planner
