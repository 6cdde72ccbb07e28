#include "planner/outlook.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "planner/rules.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

constexpr int kMaxContacts = 64;
// Caps of the D's grid (1 + 16 x 32 points at most).
constexpr int kMaxDRings = 16;
constexpr int kMaxDAngles = 32;

// Bit i set: ball i touches the cue ball. Balls past the 64th are never touching
// (tables are validated to physics::limits::kMaxBalls = 32).
using TouchMask = std::uint64_t;
constexpr size_t kMaskBits = 64;

bool Touches(TouchMask m, size_t i) { return i < kMaskBits && ((m >> i) & 1u) != 0; }

TouchMask TouchingBalls(const TableState& table, int cue, double radius) {
  TouchMask m = 0;
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const size_t n = std::min(table.balls.size(), kMaskBits);
  for (size_t i = 0; i < n; ++i) {
    if (static_cast<int>(i) == cue) continue;
    if ((table.balls[i].position - c).norm() <= 2 * radius + kTouchingGap) m |= TouchMask{1} << i;
  }
  return m;
}

// The cue ball's centre moving from c to g (direction u) passes every ball but the
// cue ball and `target` by `clearance`; a touching ball blocks a heading towards it
// and is ignored by one away from it (the player plays away from it).
bool PathClear(const TableState& table, int cue, int target, const Vec2& c, const Vec2& g,
               const Vec2& u, double clearance, TouchMask touching) {
  // geometry.h's SegmentDistance, squared, behind a box test: the inner loop.
  const Vec2 d = g - c;
  const double len2 = d.squaredNorm();
  const double inv = len2 > 0 ? 1 / len2 : 0.0;
  const double c2 = clearance * clearance;
  const double x0 = std::min(c.x(), g.x()) - clearance, x1 = std::max(c.x(), g.x()) + clearance;
  const double y0 = std::min(c.y(), g.y()) - clearance, y1 = std::max(c.y(), g.y()) + clearance;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const int k = static_cast<int>(i);
    if (k == cue || k == target) continue;
    const Vec2& p = table.balls[i].position;
    if (Touches(touching, i)) {
      if (PlaysInto(u, p - c)) return false;
      continue;
    }
    if (p.x() < x0 || p.x() > x1 || p.y() < y0 || p.y() > y1) continue;
    const Vec2 cp = p - c;
    const double t = std::clamp(cp.dot(d) * inv, 0.0, 1.0);
    if ((cp - t * d).squaredNorm() < c2) return false;
  }
  return true;
}

// The heading of the straight stroke whose line passes the ball's centre at impact
// parameter b (m, geometry.h's cut sign: b = 2R sin(cut)) when it is open (clear
// path, room for the cue), else nullopt.
std::optional<double> OpenContact(const TableState& table, int cue, int ball, double b,
                                  const PotContext& ctx, TouchMask touching) {
  const double r = ctx.table->ball_radius();
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const Vec2 o = table.balls[static_cast<size_t>(ball)].position;
  const double d = (o - c).norm();
  if (!(d > std::abs(b)) || !(d > 2 * r)) return std::nullopt;
  // The heading: the direction to the ball turned by -asin(b / d).
  const Vec2 to = (o - c) / d;
  const double sb = b / d, cb = std::sqrt(1 - sb * sb);
  const Vec2 u = cb * to - sb * Left(to);
  const double along = d * cb - std::sqrt(std::max(0.0, 4 * r * r - b * b));
  const Vec2 g = c + along * u;
  if (!PathClear(table, cue, ball, c, g, u, 2 * r + ctx.path_clearance, touching)) return std::nullopt;
  const double h = Direction(u);
  if (CueMargin(table, cue, h, ctx.cue, *ctx.table) < 0) return std::nullopt;
  return h;
}

std::optional<double> FirstOpenContact(const TableState& table, int cue, int ball,
                                       const PotContext& ctx, int contacts, TouchMask touching) {
  const int n = std::clamp(contacts, 1, kMaxContacts);
  const double b_max = 2 * ctx.table->ball_radius() * std::sin(std::min(ctx.max_cut, physics::kPi / 2));
  const int span = std::max(1, n - 1);
  // Offsets t = 2i - (n - 1), i = 0..n-1, the smallest |t| first (the full ball).
  for (int m = (n - 1) % 2; m <= n - 1; m += 2) {
    for (int sign : {1, -1}) {
      if (m == 0 && sign < 0) continue;
      const double b = b_max * sign * m / span;
      if (const auto h = OpenContact(table, cue, ball, b, ctx, touching)) return h;
    }
  }
  return std::nullopt;
}

bool CanHit(const TableState& table, int cue, int ball, const PotContext& ctx, int contacts,
            TouchMask touching) {
  return Touches(touching, static_cast<size_t>(ball)) ||
         FirstOpenContact(table, cue, ball, ctx, contacts, touching).has_value();
}

SnookerCheck CheckWith(const TableState& table, int cue, BallOn on, const PotContext& ctx, int contacts,
                       TouchMask touching) {
  SnookerCheck out;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (static_cast<int>(i) == cue) continue;
    const bool is_on = IsLegalTarget(on, table.balls[i].kind);
    if (Touches(touching, i)) {
      if (out.touching < 0) out.touching = static_cast<int>(i);
      out.touching_on = out.touching_on || is_on;
    }
    if (!is_on) continue;
    ++out.balls_on;
    if (CanHit(table, cue, static_cast<int>(i), ctx, contacts, touching)) ++out.hittable;
  }
  out.hittable_share = out.balls_on > 0 ? static_cast<double>(out.hittable) / out.balls_on : 0.0;
  out.snookered = out.balls_on > 0 && out.hittable == 0;
  return out;
}

double Penalty(BallKind kind) { return std::max(4, Value(kind)); }

// The one-cushion escape off cushion nose `s` to ball `ball`, or nullopt.
std::optional<Escape> EscapeOff(const TableState& table, int cue, int ball, int s,
                                const PotContext& ctx, const OutlookOptions& options,
                                TouchMask touching) {
  const physics::TableModel& model = *ctx.table;
  const double r = model.ball_radius();
  const physics::CushionSegment& seg = model.segments()[static_cast<size_t>(s)];
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const Vec2 o = table.balls[static_cast<size_t>(ball)].position;
  const Vec2 n = seg.normal;
  const Vec2 line0 = seg.p0 + model.cushion_contact_distance() * n;
  const double len = (seg.p1 - seg.p0).norm();
  const Vec2 dir = (seg.p1 - seg.p0) / len;
  const double hc = (c - line0).dot(n), ho = (o - line0).dot(n);
  if (!(hc > 0) || !(ho > 0)) return std::nullopt;
  // The mirror image of o in the line: the bounce where the line meets c -> image.
  const double sc = (c - line0).dot(dir), so = (o - line0).dot(dir);
  const double sp = sc + (so - sc) * hc / (hc + ho);
  if (sp < r || sp > len - r) return std::nullopt;
  const Vec2 p = line0 + sp * dir;
  const Vec2 leg1 = p - c, leg2 = o - p;
  if (!(leg1.norm() > 0) || !(leg2.norm() > 2 * r)) return std::nullopt;
  const Vec2 u1 = leg1.normalized(), u2 = leg2.normalized();
  const Vec2 contact = o - 2 * r * u2;
  const double clearance = 2 * r + ctx.path_clearance;
  if (!PathClear(table, cue, ball, c, p, u1, clearance, touching)) return std::nullopt;
  if (PathMargin(p, contact, clearance, table, cue, ball) < 0) return std::nullopt;
  Escape e;
  e.ball = ball;
  e.cushion = s;
  e.heading = Direction(leg1);
  if (CueMargin(table, cue, e.heading, ctx.cue, model) < 0) return std::nullopt;
  e.to_cushion = leg1.norm();
  e.to_ball = (contact - p).norm();
  auto sq = [](double x) { return x * x; };
  const double var = sq((e.to_cushion + e.to_ball) * ctx.noise.heading) +
                     sq(e.to_ball * options.rebound_sigma) + sq(ctx.sigma_of(cue)) + sq(ctx.sigma_of(ball));
  const double sigma = std::sqrt(var);
  e.miss_probability = sigma > 0 ? 2 * (1 - NormalCdf(2 * r / sigma)) : 0.0;
  return e;
}

// The escape with the smallest expected penalty (miss x penalty); ball -1 when none.
Escape BestEscape(const TableState& table, int cue, BallOn on, const PotContext& ctx,
                  const OutlookOptions& options, TouchMask touching) {
  Escape best;
  double best_cost = 0;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const BallKind kind = table.balls[i].kind;
    if (!IsLegalTarget(on, kind)) continue;
    for (int s = 0; s < physics::TableModel::kCushionCount; ++s) {
      const auto e = EscapeOff(table, cue, static_cast<int>(i), s, ctx, options, touching);
      if (!e) continue;
      const double cost = e->miss_probability * Penalty(kind);
      if (best.ball < 0 || cost < best_cost) {
        best = *e;
        best_cost = cost;
      }
    }
  }
  return best;
}

// The pots of the cue ball (index `cue`): EvaluatePosition, which knows no touching
// ball. A ball touching the cue ball is moved straight away from it to 2R +
// path_clearance + kTouchingGap, so that the paths' checks pass strokes away from
// it and block strokes towards it, and is made a kind that is not on, so that it
// stays an obstacle but is no pot (playing into it would be a push).
PositionValue Pots(const TableState& table, int cue, BallOn on, const PotContext& ctx,
                   const OutlookOptions& options, TouchMask touching, PocketLineCache* lines) {
  if (touching == 0) return EvaluatePosition(table, on, ctx, options.position, lines);
  TableState moved = table;
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const double apart = 2 * ctx.table->ball_radius() + ctx.path_clearance + kTouchingGap;
  for (size_t i = 0; i < moved.balls.size(); ++i) {
    if (!Touches(touching, i)) continue;
    Ball& b = moved.balls[i];
    const Vec2 away = b.position - c;
    if (away.norm() > 0) b.position = c + apart * away.normalized();
    b.kind = on == BallOn::kRed ? BallKind::kBlack : BallKind::kRed;
  }
  return EvaluatePosition(moved, on, ctx, options.position, lines);
}

Outlook OutlookWithCue(const TableState& table, int cue, BallOn on, const PotContext& ctx,
                       const OutlookOptions& options, PocketLineCache* lines) {
  Outlook out;
  const TouchMask touching = TouchingBalls(table, cue, ctx.table->ball_radius());
  const PositionValue pv = Pots(table, cue, on, ctx, options, touching, lines);
  out.pot_probability = pv.next_probability;
  out.pot_ball = pv.next_ball;
  out.pot_pocket = pv.next_pocket;
  out.position_value = pv.value;
  out.expected_points = pv.expected_points;
  out.snooker = CheckWith(table, cue, on, ctx, options.contacts, touching);
  if (!out.snooker.snookered) return out;
  out.escape = BestEscape(table, cue, on, ctx, options, touching);
  if (out.escape.ball >= 0) {
    out.foul_probability = out.escape.miss_probability;
    out.penalty = Penalty(table.balls[static_cast<size_t>(out.escape.ball)].kind);
  } else {
    // No escape in sight: the player aims at the ball on that costs least to miss.
    out.foul_probability = options.blind_miss;
    out.penalty = 7;
    for (const Ball& b : table.balls) {
      if (IsLegalTarget(on, b.kind)) out.penalty = std::min(out.penalty, Penalty(b.kind));
    }
  }
  out.expected_penalty = out.foul_probability * out.penalty;
  return out;
}

bool FreeFor(const Vec2& p, const TableState& table, double distance) {
  return std::none_of(table.balls.begin(), table.balls.end(),
                      [&](const Ball& b) { return (b.position - p).norm() < distance; });
}

// Grid point k of the D (0: the centre, then ring by ring), see the header.
Vec2 DPoint(int k, const physics::TableModel& model, const OutlookOptions& options) {
  const Vec2 centre = model.spot(physics::Colour::kBrown) - Vec2(0, options.d_inset);
  if (k == 0) return centre;
  const int angles = std::clamp(options.d_angles, 1, kMaxDAngles);
  const int ring = (k - 1) / angles + 1, j = (k - 1) % angles;
  const double rho = (model.spec().d_radius - 2 * options.d_inset) * ring / std::clamp(options.d_rings, 1, kMaxDRings);
  const double theta = angles > 1 ? physics::kPi * (1.0 + static_cast<double>(j) / (angles - 1))
                                  : 1.5 * physics::kPi;
  return centre + rho * Vec2(std::cos(theta), std::sin(theta));
}

Outlook OutlookInHand(const TableState& table, BallOn on, const PotContext& table_ctx,
                      const OutlookOptions& options, TableState& placed, PocketLineCache& lines) {
  const physics::TableModel& model = *table_ctx.table;
  // The table and the placed cue ball, in the buffer's capacity when it has grown.
  placed.balls.reserve(table.balls.size() + 1);
  placed.balls = table.balls;
  placed.balls.push_back({BallKind::kCue, Vec2::Zero()});
  const int cue = static_cast<int>(placed.balls.size()) - 1;
  // The placed ball's vision sigma, when the context gives one per ball.
  PotContext ctx = table_ctx;
  if (!ctx.position_sigma.empty()) ctx.position_sigma.resize(placed.balls.size(), ctx.noise.position);
  const int points = 1 + std::clamp(options.d_rings, 0, kMaxDRings) * std::clamp(options.d_angles, 1, kMaxDAngles);
  const double keep_off = 2 * model.ball_radius() + options.d_inset;
  Outlook best;
  double best_score = 0;
  int tried = 0;
  for (int k = 0; k < points; ++k) {
    const Vec2 p = DPoint(k, model, options);
    if (!FreeFor(p, table, keep_off)) continue;
    placed.balls[static_cast<size_t>(cue)].position = p;
    Outlook o = OutlookWithCue(placed, cue, on, ctx, options, &lines);
    const double score = o.expected_points - o.expected_penalty;
    if (tried == 0 || score > best_score) {
      best = o;
      best.placement = p;
      best_score = score;
    }
    ++tried;
  }
  best.placements_tried = tried;
  return best;
}

}  // namespace

std::optional<double> DirectHitHeading(const TableState& table, int cue, int ball,
                                       const PotContext& ctx, int contacts) {
  const TouchMask touching = TouchingBalls(table, cue, ctx.table->ball_radius());
  if (Touches(touching, static_cast<size_t>(ball))) return std::nullopt;
  return FirstOpenContact(table, cue, ball, ctx, contacts, touching);
}

bool CanHitDirectly(const TableState& table, int cue, int ball, const PotContext& ctx, int contacts) {
  return CanHit(table, cue, ball, ctx, contacts, TouchingBalls(table, cue, ctx.table->ball_radius()));
}

SnookerCheck CheckSnooker(const TableState& table, int cue, BallOn on, const PotContext& ctx,
                          int contacts) {
  return CheckWith(table, cue, on, ctx, contacts, TouchingBalls(table, cue, ctx.table->ball_radius()));
}

Outlook EvaluateOutlook(const TableState& table, BallOn on, const PotContext& ctx,
                        const OutlookOptions& options, TableState* placed, PocketLineCache* lines) {
  const int cue = table.cue_index();
  if (cue >= 0) return OutlookWithCue(table, cue, on, ctx, options, lines);
  TableState own;
  // Every placement in the D values the same object balls: their lines are worked
  // out once, in the caller's cache or in one of the call's own.
  if (lines != nullptr) return OutlookInHand(table, on, ctx, options, placed != nullptr ? *placed : own, *lines);
  PocketLineCache own_lines;
  return OutlookInHand(table, on, ctx, options, placed != nullptr ? *placed : own, own_lines);
}

}  // namespace snooker::planner
