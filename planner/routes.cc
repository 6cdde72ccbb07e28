#include "planner/routes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/core/limits.h"
#include "physics/core/shot.h"
#include "planner/geometry.h"
#include "planner/pot_estimate.h"

namespace snooker::planner {

using physics::PocketId;
using physics::Vec2;

const char* ToString(Route route) {
  switch (route) {
    case Route::kPlant: return "plant";
    case Route::kDouble: return "double";
    case Route::kKick: return "kick";
    case Route::kEscape: return "escape";
  }
  return "unknown";
}

ShotKind KindOf(Route route) { return route == Route::kEscape ? ShotKind::kEscape : ShotKind::kPot; }

std::optional<PotRoute> PotRouteOf(Route route) {
  switch (route) {
    case Route::kPlant: return PotRoute::kPlant;
    case Route::kDouble: return PotRoute::kDouble;
    case Route::kKick: return PotRoute::kKick;
    case Route::kEscape: return std::nullopt;
  }
  return std::nullopt;
}

const char* ToString(RouteRefusal r) {
  switch (r) {
    case RouteRefusal::kNone: return "kept";
    case RouteRefusal::kNotOn: return "a ball not on";
    case RouteRefusal::kCutTooThin: return "cut too thin or past 90 deg";
    case RouteRefusal::kPocketAngle: return "pocket closed to the line";
    case RouteRefusal::kNoCushionPath: return "no cushion path (jaw, mouth or glance)";
    case RouteRefusal::kCueBallPath: return "cue ball's path blocked";
    case RouteRefusal::kFirstBallPath: return "first ball's path blocked";
    case RouteRefusal::kObjectBallPath: return "object ball's path blocked";
    case RouteRefusal::kCueRoom: return "no room for the cue";
    case RouteRefusal::kUnlikely: return "estimate under the minimum";
    case RouteRefusal::kTooLong: return "kick path too long";
  }
  return "unknown";
}

double ThrowAllowance(double cut) {
  return physics::DegToRad(0.5) + physics::DegToRad(2.5) * std::abs(std::sin(cut));
}

namespace {

// Rolling deceleration mu_r g and the object ball's speed after a full contact,
// as pot_estimate.cc's TypicalContactSpeed takes them.
constexpr double kRollDecel = 0.1256;  // m/s^2
constexpr double kTransfer = 0.9;
constexpr double kSlide = 5.0 / 7.0;

// The cue-ball speed at contact that sends a ball `distance` (m) at cut `cut` to
// arrive at `arrival` (m/s): TypicalContactSpeed for another arrival speed. m/s.
double ContactSpeedFor(double arrival, double distance, double cut) {
  const double v_object = std::sqrt(arrival * arrival + 2 * kRollDecel * distance) / kSlide;
  return std::clamp(v_object / (kTransfer * std::max(std::cos(cut), 0.2)), 0.5, 5.0);
}

const Vec2& At(const TableState& table, int i) { return table.balls[static_cast<size_t>(i)].position; }

bool ValidBall(const TableState& table, int i) {
  return i >= 0 && i < static_cast<int>(table.balls.size());
}

// A ball's line into a pocket (pot_estimate.h) and where it passes the mouth centre.
struct RouteLine : PocketLine {
  Vec2 aim_point = Vec2::Zero();  // m
};

std::optional<RouteLine> LineToPocket(const PocketModel& pockets, const Vec2& from, PocketId pocket) {
  const auto line = LineIntoPocket(pockets, from, pocket);
  if (!line) return std::nullopt;
  RouteLine out;
  static_cast<PocketLine&>(out) = *line;
  out.aim_point = pockets.table().pocket(pocket).mouth_centre +
                  line->window.centre() * Left(physics::HeadingVector(line->direction));
  return out;
}

// d(object direction) / d(cut) of the ghost-ball construction (search.cc's
// PredictCut slope), kept from collapsing when the balls nearly touch.
double DirectionPerCut(const Vec2& cue, const Vec2& object, double heading, double cut, double r) {
  const double d = (object - cue).norm();
  const double phi = WrapAngle(Direction(object - cue) - heading);
  return std::max(1 - 2 * r * std::cos(cut) / (d * std::max(std::cos(phi), 1e-3)), 0.1);
}

// The heading bracket of a kCut aim: the headings of its cut bracket's ends.
void SpanHeadings(RouteCandidate& cand, const Vec2& cue, const Vec2& first, double r) {
  AimBracket heading;
  for (double c : {cand.cut + cand.cut_bracket.lo, cand.cut + cand.cut_bracket.hi}) {
    if (const auto h = HeadingForCut(cue, first, c, r)) {
      const double off = WrapAngle(*h - cand.heading);
      heading.lo = std::min(heading.lo, off);
      heading.hi = std::max(heading.hi, off);
    }
  }
  cand.heading_bracket = heading;
}

// Sets a kCut aim: the cue ball's ghost aim on the first ball, the direction it
// sends the first ball along and that direction's bracket; the cut bracket covers
// the direction bracket and the throw (on the side a thicker contact needs: the
// throw turns the object ball towards the cue ball's heading), the heading bracket
// the headings of the cut bracket's ends.
void SetCutAim(RouteCandidate& cand, const Vec2& cue, const Vec2& first, const GhostAim& aim,
               double direction, const AimBracket& directions, double max_cut, double r) {
  cand.aim = AimBy::kCut;
  cand.heading = aim.heading;
  cand.cut = aim.cut;
  cand.first_direction = direction;
  cand.direction_bracket = directions;
  const double slope = DirectionPerCut(cue, first, aim.heading, aim.cut, r);
  AimBracket cut{directions.lo / slope, directions.hi / slope};
  const double t = ThrowAllowance(aim.cut);
  if (aim.cut >= -physics::DegToRad(1)) cut.hi += t;
  if (aim.cut <= physics::DegToRad(1)) cut.lo -= t;
  cut.lo = std::max(cut.lo, -max_cut - aim.cut);
  cut.hi = std::min(cut.hi, max_cut - aim.cut);
  cand.cut_bracket = {std::min(cut.lo, 0.0), std::max(cut.hi, 0.0)};
  SpanHeadings(cand, cue, first, r);
}

// The standard deviation of the outgoing direction at contact i of `path` that the
// search cannot aim away: the speed noise through the rebound, and the extra.
double ReboundSigma(const CushionPath& path, int i, const PotContext& ctx, const RouteOptions& options) {
  const double speed = ReboundSpeedSensitivity(path.contacts[static_cast<size_t>(i)].incidence, path.sliding) *
                       ctx.noise.speed_fraction;
  return std::hypot(speed, options.rebound_extra_sigma);
}

void SetProbability(RouteCandidate& cand, double mean, double sigma, const PocketWindow& window) {
  cand.window = window;
  cand.sigma = sigma;
  cand.probability = WindowProbability(mean, sigma, window);
  cand.miss_probability = 1 - cand.probability;
}

// Both balls may be hit first and potted, and one may be played onto the other:
// with a colour on only one ball of it counts, so no plant.
bool BothOn(BallOn on, BallKind a, BallKind b) {
  return IsLegalTarget(on, a) && IsLegalTarget(on, b) && (on != BallOn::kAnyColour || a == b);
}

// Refuses with `r`.
std::optional<RouteCandidate> Refuse(RouteRefusal* why, RouteRefusal r) {
  if (why) *why = r;
  return std::nullopt;
}

// B's line for a plant or a set, and what A must do for it.
struct PlantLine {
  double b_direction = 0;  // rad
  double a_direction = 0;  // rad
  double la = 0, lb = 0;   // A's travel to B's ghost position, B's to the mouth, m
  double cut_ab = 0;       // A's cut on B, rad
  double mean = 0;         // B's planned offset at the mouth, m
  PocketWindow window;
  Vec2 b_ghost = Vec2::Zero();  // where A meets B
  Vec2 b_aim = Vec2::Zero();    // where B's line passes the mouth
};

std::optional<PlantLine> PlantGeometry(const Vec2& a, const Vec2& b, bool set, PocketId pocket,
                                       const std::optional<RouteLine>& line, const PotContext& ctx,
                                       const RouteOptions& options, RouteRefusal& reason) {
  const double r = ctx.table->ball_radius();
  PlantLine pl;
  if (!set) {
    if (!line) {
      reason = RouteRefusal::kPocketAngle;
      return std::nullopt;
    }
    const auto ab = AimAlong(a, b, line->direction, r);
    if (!ab || std::abs(ab->cut) > ctx.max_cut) {
      reason = RouteRefusal::kCutTooThin;
      return std::nullopt;
    }
    pl = {line->direction, ab->heading, (ab->ghost - a).norm(), line->distance, ab->cut,
          line->window.centre(), line->window, ab->ghost, line->aim_point};
    return pl;
  }
  // A set: B leaves along the line of centres, the throw turning it at most set_throw
  // towards the pocket's centred line.
  const double centres = Direction(b - a);
  double want = centres;
  if (line) {
    want += std::clamp(WrapAngle(line->direction - centres), -options.set_throw, options.set_throw);
  }
  pl.window = ctx.pockets->Window(pocket, want, kTypicalArrivalSpeed);
  const Vec2 u = physics::HeadingVector(want);
  const Vec2 mouth = ctx.table->pocket(pocket).mouth_centre;
  pl.lb = (mouth - b).dot(u);
  if (pl.window.empty || !(pl.lb > 0)) {
    reason = RouteRefusal::kPocketAngle;
    return std::nullopt;
  }
  pl.b_direction = want;
  pl.a_direction = centres;
  pl.mean = (b - mouth).dot(Left(u));
  pl.b_ghost = a;
  pl.b_aim = b + pl.lb * u;
  return pl;
}

std::optional<RouteCandidate> PlantFrom(const TableState& table, int cue, int first, int potted,
                                        PocketId pocket, const std::optional<RouteLine>& line,
                                        const PotContext& ctx, const RouteOptions& options,
                                        RouteRefusal* why) {
  RouteRefusal reason = RouteRefusal::kNone;
  const double r = ctx.table->ball_radius();
  const Vec2 c = At(table, cue), a = At(table, first), b = At(table, potted);
  const bool set = (a - b).norm() < 2 * r + options.set_gap;
  const auto pl = PlantGeometry(a, b, set, pocket, line, ctx, options, reason);
  if (!pl) return Refuse(why, reason);
  const auto aim = AimAlong(c, a, pl->a_direction, r);
  if (!aim || std::abs(aim->cut) > ctx.max_cut) return Refuse(why, RouteRefusal::kCutTooThin);
  const double clear = 2 * r + ctx.path_clearance;
  const std::array<int, 2> cue_skip = {cue, first};
  const std::array<int, 3> ball_skip = {cue, first, potted};
  if (SegmentMargin(c, aim->ghost, clear, table, cue_skip) < 0) return Refuse(why, RouteRefusal::kCueBallPath);
  if (!set && SegmentMargin(a, pl->b_ghost, clear, table, ball_skip) < 0) {
    return Refuse(why, RouteRefusal::kFirstBallPath);
  }
  if (SegmentMargin(b, pl->b_aim, clear, table, ball_skip) < 0) return Refuse(why, RouteRefusal::kObjectBallPath);
  RouteCandidate cand;
  cand.route = Route::kPlant;
  cand.set = set;
  cand.first_ball = first;
  cand.potted_ball = potted;
  cand.pocket = pocket;
  cand.object_direction = pl->b_direction;
  cand.ghost = pl->b_ghost;
  cand.distance = pl->lb;
  cand.cue_margin = CueMargin(table, cue, aim->heading, ctx.cue, *ctx.table);
  if (cand.cue_margin < 0) return Refuse(why, RouteRefusal::kCueRoom);
  // The estimate (routes.h): A's lateral error at B through B's lever kB.
  const NoiseModel& noise = ctx.noise;
  const double sig_b = ctx.sigma_of(potted);
  const double contact_b = TypicalContactSpeed(pl->lb, pl->cut_ab);
  const double t_b = ctx.throws->At(pl->cut_ab, contact_b).per_log_speed * noise.speed_fraction;
  double var = 0;
  if (set) {
    const double s_a = ctx.sigma_of(first);
    var = pl->lb * pl->lb * (s_a * s_a + sig_b * sig_b) / (4 * r * r) + sig_b * sig_b;
  } else {
    const double contact_a = ContactSpeedFor(contact_b, pl->la, aim->cut);
    const double s_a = LateralSigma(c, a, aim->heading, aim->cut, pl->la, contact_a, ctx.sigma_of(cue),
                                    ctx.sigma_of(first), noise, *ctx.throws, r);
    const double cos_ab = std::max(std::cos(pl->cut_ab), 1e-3);
    const double kb = pl->lb / (2 * r * cos_ab);
    var = kb * kb * s_a * s_a + sig_b * sig_b * (kb * kb + 1 + 2 * kb * cos_ab);
    cand.heading_gain = kb * HeadingGain(c, a, aim->heading, aim->cut, pl->la, r);
  }
  var += pl->lb * pl->lb * t_b * t_b;
  SetProbability(cand, pl->mean, std::sqrt(var), pl->window);
  if (set) {
    SetCutAim(cand, c, a, *aim, pl->a_direction, {-options.set_throw, options.set_throw}, ctx.max_cut, r);
    cand.cut_bracket = {std::min(0.0, std::max(-options.set_cut_range, -ctx.max_cut - aim->cut)),
                        std::max(0.0, std::min(options.set_cut_range, ctx.max_cut - aim->cut))};
    SpanHeadings(cand, c, a, r);
  } else {
    // A's direction turns B by about la / (2R cos cAB) times as much: the throw on
    // B asks that much less of A.
    const double half = ThrowAllowance(pl->cut_ab) * 2 * r * std::cos(pl->cut_ab) / std::max(pl->la, 2 * r) +
                        options.paths.bracket_floor;
    SetCutAim(cand, c, a, *aim, pl->a_direction, {-half, half}, ctx.max_cut, r);
  }
  if (cand.probability < options.min_probability) return Refuse(why, RouteRefusal::kUnlikely);
  if (why) *why = RouteRefusal::kNone;
  return cand;
}

}  // namespace

std::optional<RouteCandidate> AssessPlant(const TableState& table, int cue, BallOn on, int first,
                                          int potted, PocketId pocket, const PotContext& ctx,
                                          const RouteOptions& options, RouteRefusal* why) {
  if (!ValidBall(table, cue) || !ValidBall(table, first) || !ValidBall(table, potted) || first == potted ||
      !BothOn(on, table.balls[static_cast<size_t>(first)].kind, table.balls[static_cast<size_t>(potted)].kind)) {
    return Refuse(why, RouteRefusal::kNotOn);
  }
  const auto line = LineToPocket(*ctx.pockets, At(table, potted), pocket);
  return PlantFrom(table, cue, first, potted, pocket, line, ctx, options, why);
}

}  // namespace snooker::planner

namespace snooker::planner {
namespace {

std::optional<RouteCandidate> DoubleFrom(const TableState& table, int cue, int object, PocketId pocket,
                                         CushionLine line, const PotContext& ctx,
                                         const RouteOptions& options, RouteRefusal* why) {
  const double r = ctx.table->ball_radius();
  const Vec2 c = At(table, cue), o = At(table, object);
  const physics::Pocket& p = ctx.table->pocket(pocket);
  const std::array<CushionLine, 1> lines = {line};
  CushionPathOptions path_options = options.paths;
  path_options.sliding = true;  // the object ball leaves the contact without topspin
  // Aim at the window's centre for the last leg's direction: settled in two passes,
  // as EstimatePot settles a direct pot's.
  Vec2 target = p.mouth_centre;
  std::optional<CushionPath> path;
  PocketWindow window;
  for (int pass = 0; pass < 3; ++pass) {
    path = MirrorPath(*ctx.table, o, target, lines, path_options);
    if (!path) return Refuse(why, RouteRefusal::kNoCushionPath);
    if (pass == 2) break;
    window = ctx.pockets->Window(pocket, path->final_direction, kTypicalArrivalSpeed);
    if (window.empty) return Refuse(why, RouteRefusal::kPocketAngle);
    target = p.mouth_centre + window.centre() * Left(physics::HeadingVector(path->final_direction));
  }
  const auto aim = AimAlong(c, o, path->heading, r);
  if (!aim || std::abs(aim->cut) > ctx.max_cut) return Refuse(why, RouteRefusal::kCutTooThin);
  const double clear = 2 * r + ctx.path_clearance;
  const std::array<int, 2> skip = {cue, object};
  if (SegmentMargin(c, aim->ghost, clear, table, skip) < 0) return Refuse(why, RouteRefusal::kCueBallPath);
  if (LegsMargin(*path, clear, table, object, cue) < 0) return Refuse(why, RouteRefusal::kObjectBallPath);
  RouteCandidate cand;
  cand.route = Route::kDouble;
  cand.first_ball = object;
  cand.potted_ball = object;
  cand.pocket = pocket;
  cand.object_direction = path->final_direction;
  cand.ghost = aim->ghost;
  cand.distance = path->length;
  cand.cue_margin = CueMargin(table, cue, aim->heading, ctx.cue, *ctx.table);
  if (cand.cue_margin < 0) return Refuse(why, RouteRefusal::kCueRoom);
  // The direct pot's terms over the unfolded length, and the cushion's own error.
  const double contact = TypicalContactSpeed(path->length, aim->cut);
  const double lateral = LateralSigma(c, o, aim->heading, aim->cut, path->length, contact, ctx.sigma_of(cue),
                                      ctx.sigma_of(object), ctx.noise, *ctx.throws, r);
  const double bounce = ReboundSigma(*path, 0, ctx, options) * path->LengthAfter(0);
  SetProbability(cand, window.centre(), std::hypot(lateral, bounce), window);
  cand.heading_gain = HeadingGain(c, o, aim->heading, aim->cut, path->length, r);
  SetCutAim(cand, c, o, *aim, path->heading, path->bracket, ctx.max_cut, r);
  cand.path = path;
  if (cand.probability < options.min_probability) return Refuse(why, RouteRefusal::kUnlikely);
  if (why) *why = RouteRefusal::kNone;
  return cand;
}

// A kick's object-ball side, the same for every cushion sequence: its line into
// the pocket, its ghost-ball position, and whether that line is clear.
struct KickTarget {
  std::optional<RouteLine> line;
  Vec2 ghost = Vec2::Zero();
  bool clear = false;
};

KickTarget KickTargetFor(const TableState& table, int cue, int object, PocketId pocket, const PotContext& ctx) {
  KickTarget k;
  k.line = LineToPocket(*ctx.pockets, At(table, object), pocket);
  if (!k.line) return k;
  const double r = ctx.table->ball_radius();
  k.ghost = At(table, object) - 2 * r * physics::HeadingVector(k.line->direction);
  const std::array<int, 2> skip = {cue, object};
  k.clear = SegmentMargin(At(table, object), k.line->aim_point, 2 * r + ctx.path_clearance, table, skip) >= 0;
  return k;
}

std::optional<RouteCandidate> KickFrom(const TableState& table, int cue, int object, PocketId pocket,
                                       std::span<const CushionLine> lines, const KickTarget& target,
                                       const PotContext& ctx, const RouteOptions& options, RouteRefusal* why) {
  if (!target.line) return Refuse(why, RouteRefusal::kPocketAngle);
  if (!target.clear) return Refuse(why, RouteRefusal::kObjectBallPath);
  const RouteLine* line = &*target.line;
  const double r = ctx.table->ball_radius();
  const Vec2 c = At(table, cue), o = At(table, object);
  const Vec2 ghost = target.ghost;
  const auto path = MirrorPath(*ctx.table, c, ghost, lines, options.paths);
  if (!path) return Refuse(why, RouteRefusal::kNoCushionPath);
  if (path->length > options.max_kick_length) return Refuse(why, RouteRefusal::kTooLong);
  const double cut = WrapAngle(line->direction - path->final_direction);
  if (!(std::abs(cut) <= ctx.max_cut)) return Refuse(why, RouteRefusal::kCutTooThin);
  const double clear = 2 * r + ctx.path_clearance;
  if (LegsMargin(*path, clear, table, cue, -1, object) < 0) return Refuse(why, RouteRefusal::kCueBallPath);
  RouteCandidate cand;
  cand.route = Route::kKick;
  cand.first_ball = object;
  cand.potted_ball = object;
  cand.pocket = pocket;
  cand.aim = AimBy::kHeading;
  cand.heading = path->heading;
  cand.cut = cut;
  cand.first_direction = line->direction;
  cand.object_direction = line->direction;
  cand.ghost = ghost;
  cand.distance = line->distance;
  cand.cue_margin = CueMargin(table, cue, path->heading, ctx.cue, *ctx.table);
  if (cand.cue_margin < 0) return Refuse(why, RouteRefusal::kCueRoom);
  // The direct pot from a cue ball as far back along the unfolded path, and each
  // cushion's error through the lever k.
  const Vec2 virtual_cue = ghost - path->length * physics::HeadingVector(path->final_direction);
  const double contact = TypicalContactSpeed(line->distance, cut);
  const double lateral = LateralSigma(virtual_cue, o, path->final_direction, cut, line->distance, contact,
                                      ctx.sigma_of(cue), ctx.sigma_of(object), ctx.noise, *ctx.throws, r);
  const double cos_c = std::max(std::cos(cut), 1e-3);
  const double k = line->distance / (2 * r * cos_c);
  double var = lateral * lateral;
  for (int i = 0; i < path->cushions; ++i) {
    const double b = k * ReboundSigma(*path, i, ctx, options) * path->LengthAfter(i);
    var += b * b;
  }
  SetProbability(cand, line->window.centre(), std::sqrt(var), line->window);
  cand.heading_gain = HeadingGain(virtual_cue, o, path->final_direction, cut, line->distance, r);
  // The mirror's error, and the throw: a cut thicker by up to ThrowAllowance.
  const double throw_turn = ThrowAllowance(cut) * 2 * r * cos_c / path->length;
  cand.heading_bracket = {path->bracket.lo - throw_turn, path->bracket.hi + throw_turn};
  cand.path = path;
  if (cand.probability < options.min_probability) return Refuse(why, RouteRefusal::kUnlikely);
  if (why) *why = RouteRefusal::kNone;
  return cand;
}

// An escape's clear offsets: where, across the object ball, the cue ball's path
// may pass its centre (offset e, m, positive to the left seen along the unfolded
// path) and hit it before any other ball. Offsets are sampled across
// (-2R + edge, 2R - edge); each sample turns the unfolded path about the cue ball
// and ends it where it meets the object ball; a sample is clear when every other
// ball's image, for the leg it lies by, stays `clear` from it (the object ball too
// for the legs before the last: an escape meets it after its cushions).
struct ClearRun {
  bool any = false;
  double lo = 0, hi = 0;  // m
};

ClearRun EscapeClearRun(const TableState& table, int cue, int object, const CushionPath& path,
                        double clear, const RouteOptions& options, double r) {
  const Vec2 s = path.start();
  const Vec2 tu = path.Unfold(path.cushions, path.target());
  const Vec2 u = (tu - s).normalized(), nl = Left(u);
  std::array<double, 4> cum{};
  for (int j = 0; j < path.leg_count(); ++j) cum[static_cast<size_t>(j + 1)] = cum[static_cast<size_t>(j)] + path.legs[static_cast<size_t>(j)];
  struct Near {
    Vec2 q;
    int leg;
  };
  std::array<Near, 3 * physics::limits::kMaxBalls> near{};
  size_t count = 0;
  for (size_t i = 0; i < table.balls.size() && i < static_cast<size_t>(physics::limits::kMaxBalls); ++i) {
    if (static_cast<int>(i) == cue) continue;
    const int legs = static_cast<int>(i) == object ? path.cushions : path.leg_count();
    for (int j = 0; j < legs; ++j) {
      const Vec2 q = path.Unfold(j, table.balls[i].position);
      const double along = (q - s).dot(u), side = (q - s).dot(nl);
      if (std::abs(side) > 2 * r + clear) continue;
      if (along < cum[static_cast<size_t>(j)] - clear || along > cum[static_cast<size_t>(j + 1)] + clear) continue;
      near[count++] = {q, j};
    }
  }
  const int n = std::max(3, options.escape_offsets | 1);
  const double half = 2 * r - options.escape_edge;
  const double step = 2 * half / (n - 1);
  ClearRun best;
  int run_start = -1;
  for (int k = 0; k <= n; ++k) {
    bool free = false;
    if (k < n) {
      const double e = -half + k * step;
      const Vec2 ue = (tu + e * nl - s).normalized();
      const double lateral = Cross(ue, tu - s);
      const double meet = (tu - s).dot(ue) - std::sqrt(std::max(0.0, 4 * r * r - lateral * lateral));
      free = true;
      for (size_t m = 0; m < count && free; ++m) {
        const double a = cum[static_cast<size_t>(near[m].leg)];
        const double b = std::min(cum[static_cast<size_t>(near[m].leg + 1)], meet);
        if (b > a && SegmentDistance(s + a * ue, s + b * ue, near[m].q) < clear) free = false;
      }
    }
    if (free && run_start < 0) run_start = k;
    if (!free && run_start >= 0) {
      const double lo = std::max(-half, -half + (run_start - 0.5) * step);
      const double hi = std::min(half, -half + (k - 0.5) * step);
      if (!best.any || hi - lo > best.hi - best.lo) best = {true, lo, hi};
      run_start = -1;
    }
  }
  return best;
}

std::optional<RouteCandidate> EscapeFrom(const TableState& table, int cue, int object,
                                         std::span<const CushionLine> lines, const PotContext& ctx,
                                         const RouteOptions& options, RouteRefusal* why) {
  const double r = ctx.table->ball_radius();
  const Vec2 c = At(table, cue), o = At(table, object);
  const auto centre_path = MirrorPath(*ctx.table, c, o, lines, options.paths);
  if (!centre_path) return Refuse(why, RouteRefusal::kNoCushionPath);
  const double clear = 2 * r + ctx.path_clearance;
  const ClearRun run = EscapeClearRun(table, cue, object, *centre_path, clear, options, r);
  if (!run.any) return Refuse(why, RouteRefusal::kCueBallPath);
  // The path through the run's centre, then its legs checked as they are (the last
  // one up to where the cue ball meets the object ball).
  const double mean = 0.5 * (run.lo + run.hi);
  const Vec2 tu = centre_path->Unfold(centre_path->cushions, o);
  const Vec2 nl = Left((tu - c).normalized());
  const auto path = MirrorPath(*ctx.table, c, centre_path->Fold(centre_path->cushions, tu + mean * nl), lines,
                               options.paths);
  if (!path) return Refuse(why, RouteRefusal::kNoCushionPath);
  const Vec2 last = path->points[static_cast<size_t>(path->cushions)];
  const Vec2 ul = physics::HeadingVector(path->final_direction);
  const double along = (o - last).dot(ul);
  const double side2 = (o - last).squaredNorm() - along * along;
  const double meet = along - std::sqrt(std::max(0.0, 4 * r * r - side2));
  if (side2 >= 4 * r * r || !(meet > 0)) return Refuse(why, RouteRefusal::kCueBallPath);
  const Vec2 ghost = last + meet * ul;
  const std::array<int, 1> cue_only = {cue};
  const std::array<int, 2> cue_object = {cue, object};
  for (int j = 0; j < path->cushions; ++j) {
    if (SegmentMargin(path->points[static_cast<size_t>(j)], path->points[static_cast<size_t>(j + 1)], clear, table,
                      cue_only) < 0) {
      return Refuse(why, RouteRefusal::kCueBallPath);
    }
  }
  if (SegmentMargin(last, ghost, clear, table, cue_object) < 0) return Refuse(why, RouteRefusal::kCueBallPath);
  RouteCandidate cand;
  cand.route = Route::kEscape;
  cand.first_ball = object;
  cand.aim = AimBy::kHeading;
  cand.heading = path->heading;
  cand.cut = WrapAngle(Direction(o - ghost) - path->final_direction);
  cand.first_direction = path->final_direction;
  cand.object_direction = Direction(o - ghost);
  cand.ghost = ghost;
  cand.distance = path->length - (path->target() - ghost).norm();
  cand.cue_margin = CueMargin(table, cue, path->heading, ctx.cue, *ctx.table);
  if (cand.cue_margin < 0) return Refuse(why, RouteRefusal::kCueRoom);
  // The cue ball's lateral error at the ball against the clear run.
  double var = std::pow(ctx.noise.heading * cand.distance, 2) + std::pow(ctx.sigma_of(cue), 2) +
               std::pow(ctx.sigma_of(object), 2);
  for (int i = 0; i < path->cushions; ++i) var += std::pow(ReboundSigma(*path, i, ctx, options) * path->LengthAfter(i), 2);
  cand.sigma = std::sqrt(var);
  cand.probability = std::max(0.0, NormalCdf((run.hi - mean) / cand.sigma) - NormalCdf((run.lo - mean) / cand.sigma));
  cand.miss_probability = 1 - cand.probability;
  // The mirror's error, and every heading whose path stays in the clear run.
  cand.heading_bracket = {path->bracket.lo + (run.lo - mean) / path->length,
                          path->bracket.hi + (run.hi - mean) / path->length};
  cand.path = path;
  if (why) *why = RouteRefusal::kNone;
  return cand;
}

}  // namespace

std::optional<RouteCandidate> AssessDouble(const TableState& table, int cue, BallOn on, int object,
                                           PocketId pocket, CushionLine line, const PotContext& ctx,
                                           const RouteOptions& options, RouteRefusal* why) {
  if (!ValidBall(table, cue) || !ValidBall(table, object) || object == cue ||
      !IsLegalTarget(on, table.balls[static_cast<size_t>(object)].kind)) {
    return Refuse(why, RouteRefusal::kNotOn);
  }
  return DoubleFrom(table, cue, object, pocket, line, ctx, options, why);
}

std::optional<RouteCandidate> AssessKick(const TableState& table, int cue, BallOn on, int object,
                                         PocketId pocket, std::span<const CushionLine> lines,
                                         const PotContext& ctx, const RouteOptions& options,
                                         RouteRefusal* why) {
  if (!ValidBall(table, cue) || !ValidBall(table, object) || object == cue ||
      !IsLegalTarget(on, table.balls[static_cast<size_t>(object)].kind)) {
    return Refuse(why, RouteRefusal::kNotOn);
  }
  return KickFrom(table, cue, object, pocket, lines, KickTargetFor(table, cue, object, pocket, ctx), ctx, options,
                  why);
}

std::optional<RouteCandidate> AssessEscape(const TableState& table, int cue, BallOn on, int object,
                                           std::span<const CushionLine> lines, const PotContext& ctx,
                                           const RouteOptions& options, RouteRefusal* why) {
  if (!ValidBall(table, cue) || !ValidBall(table, object) || object == cue ||
      !IsLegalTarget(on, table.balls[static_cast<size_t>(object)].kind)) {
    return Refuse(why, RouteRefusal::kNotOn);
  }
  return EscapeFrom(table, cue, object, lines, ctx, options, why);
}

namespace {

// The cushion sequences in the order enumerators try them: each line alone, then
// (up to `cushions` = 2) every ordered pair of different lines.
struct Sequences {
  std::array<std::array<CushionLine, 2>, kCushionLineCount * kCushionLineCount> lines{};
  std::array<int, kCushionLineCount * kCushionLineCount> size{};
  int count = 0;
};

Sequences CushionSequences(int cushions) {
  Sequences s;
  for (int a = 0; a < kCushionLineCount; ++a) {
    s.lines[static_cast<size_t>(s.count)] = {static_cast<CushionLine>(a), static_cast<CushionLine>(a)};
    s.size[static_cast<size_t>(s.count++)] = 1;
  }
  for (int a = 0; a < kCushionLineCount && cushions >= 2; ++a) {
    for (int b = 0; b < kCushionLineCount; ++b) {
      if (a == b) continue;
      s.lines[static_cast<size_t>(s.count)] = {static_cast<CushionLine>(a), static_cast<CushionLine>(b)};
      s.size[static_cast<size_t>(s.count++)] = 2;
    }
  }
  return s;
}

std::span<const CushionLine> SequenceAt(const Sequences& s, int i) {
  return {s.lines[static_cast<size_t>(i)].data(), static_cast<size_t>(s.size[static_cast<size_t>(i)])};
}

void Count(RouteStats* stats, const std::optional<RouteCandidate>& cand, RouteRefusal why) {
  if (!stats) return;
  ++stats->considered;
  if (!cand) ++stats->refused[static_cast<size_t>(why)];
}

// An escape's miss probability in steps of kMissStep: escapes whose chances differ
// by less are equal for ranking (most clear escapes miss with a chance of 1e-6 or
// less, and a difference there says nothing).
constexpr double kMissStep = 1e-3;
int MissRank(const RouteCandidate& c) {
  return static_cast<int>(std::floor(std::clamp(c.miss_probability, 0.0, 1.0) / kMissStep));
}

// Pots: most likely first. Escapes: least likely to miss (MissRank), then fewer
// cushions, then shorter. Ties keep the enumeration order (stable), for determinism.
void Rank(std::vector<RouteCandidate>& out, const RouteOptions& options, bool escapes) {
  if (escapes) {
    std::stable_sort(out.begin(), out.end(), [](const RouteCandidate& a, const RouteCandidate& b) {
      if (MissRank(a) != MissRank(b)) return MissRank(a) < MissRank(b);
      const int ca = a.path ? a.path->cushions : 0, cb = b.path ? b.path->cushions : 0;
      if (ca != cb) return ca < cb;
      return a.distance < b.distance;
    });
  } else {
    std::stable_sort(out.begin(), out.end(), [](const RouteCandidate& a, const RouteCandidate& b) {
      return a.probability > b.probability;
    });
  }
  if (static_cast<int>(out.size()) > std::max(0, options.max_candidates)) {
    out.resize(static_cast<size_t>(std::max(0, options.max_candidates)));
  }
}

bool OnAndNotCue(const TableState& table, int cue, BallOn on, int i) {
  return i != cue && IsLegalTarget(on, table.balls[static_cast<size_t>(i)].kind);
}

}  // namespace

std::vector<RouteCandidate> EnumeratePlants(const TableState& table, int cue, BallOn on,
                                            const PotContext& ctx, const RouteOptions& options,
                                            RouteStats* stats) {
  std::vector<RouteCandidate> out;
  if (!ValidBall(table, cue)) return out;
  const int n = static_cast<int>(table.balls.size());
  // Each potted ball's lines into the pockets, once.
  std::vector<std::array<std::optional<RouteLine>, physics::kPocketCount>> lines(static_cast<size_t>(n));
  for (int b = 0; b < n; ++b) {
    if (!OnAndNotCue(table, cue, on, b)) continue;
    for (int k = 0; k < physics::kPocketCount; ++k) {
      lines[static_cast<size_t>(b)][static_cast<size_t>(k)] =
          LineToPocket(*ctx.pockets, At(table, b), static_cast<PocketId>(k));
    }
  }
  for (int a = 0; a < n; ++a) {
    if (!OnAndNotCue(table, cue, on, a)) continue;
    for (int b = 0; b < n; ++b) {
      if (b == a || !OnAndNotCue(table, cue, on, b) ||
          !BothOn(on, table.balls[static_cast<size_t>(a)].kind, table.balls[static_cast<size_t>(b)].kind)) {
        continue;
      }
      for (int k = 0; k < physics::kPocketCount; ++k) {
        RouteRefusal why = RouteRefusal::kNone;
        auto cand = PlantFrom(table, cue, a, b, static_cast<PocketId>(k),
                              lines[static_cast<size_t>(b)][static_cast<size_t>(k)], ctx, options, &why);
        Count(stats, cand, why);
        if (cand) out.push_back(std::move(*cand));
      }
    }
  }
  Rank(out, options, false);
  return out;
}

std::vector<RouteCandidate> EnumerateDoubles(const TableState& table, int cue, BallOn on,
                                             const PotContext& ctx, const RouteOptions& options,
                                             RouteStats* stats) {
  std::vector<RouteCandidate> out;
  if (!ValidBall(table, cue)) return out;
  for (int o = 0; o < static_cast<int>(table.balls.size()); ++o) {
    if (!OnAndNotCue(table, cue, on, o)) continue;
    for (int k = 0; k < physics::kPocketCount; ++k) {
      for (int l = 0; l < kCushionLineCount; ++l) {
        RouteRefusal why = RouteRefusal::kNone;
        auto cand = DoubleFrom(table, cue, o, static_cast<PocketId>(k), static_cast<CushionLine>(l), ctx,
                               options, &why);
        Count(stats, cand, why);
        if (cand) out.push_back(std::move(*cand));
      }
    }
  }
  Rank(out, options, false);
  return out;
}

std::vector<RouteCandidate> EnumerateKicks(const TableState& table, int cue, BallOn on,
                                           const PotContext& ctx, const RouteOptions& options,
                                           RouteStats* stats) {
  std::vector<RouteCandidate> out;
  if (!ValidBall(table, cue)) return out;
  const Sequences seq = CushionSequences(options.kick_cushions);
  for (int o = 0; o < static_cast<int>(table.balls.size()); ++o) {
    if (!OnAndNotCue(table, cue, on, o)) continue;
    for (int k = 0; k < physics::kPocketCount; ++k) {
      const KickTarget target = KickTargetFor(table, cue, o, static_cast<PocketId>(k), ctx);
      for (int i = 0; i < seq.count; ++i) {
        RouteRefusal why = RouteRefusal::kNone;
        auto cand = KickFrom(table, cue, o, static_cast<PocketId>(k), SequenceAt(seq, i), target, ctx, options, &why);
        Count(stats, cand, why);
        if (cand) out.push_back(std::move(*cand));
      }
    }
  }
  Rank(out, options, false);
  return out;
}

std::vector<RouteCandidate> EnumerateEscapes(const TableState& table, int cue, BallOn on,
                                             const PotContext& ctx, const RouteOptions& options,
                                             RouteStats* stats) {
  std::vector<RouteCandidate> out;
  if (!ValidBall(table, cue)) return out;
  const Sequences seq = CushionSequences(options.escape_cushions);
  for (int o = 0; o < static_cast<int>(table.balls.size()); ++o) {
    if (!OnAndNotCue(table, cue, on, o)) continue;
    for (int i = 0; i < seq.count; ++i) {
      RouteRefusal why = RouteRefusal::kNone;
      auto cand = EscapeFrom(table, cue, o, SequenceAt(seq, i), ctx, options, &why);
      Count(stats, cand, why);
      if (cand) out.push_back(std::move(*cand));
    }
  }
  Rank(out, options, true);
  return out;
}

}  // namespace snooker::planner
