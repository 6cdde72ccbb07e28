// cue_report: the cue strike's measurements for docs/cue.md, as Markdown on stdout
// (scripts/cue-report runs it and tools/cue_report.py writes the document).
//
//   cue_report strike          the strike model against Alciatore's TP A.30 and
//                              A.31 and TP B.1's measured squirt; squirt, swerve and
//                              hop tables.
//   cue_report cushion         the planner with the cue ball against a cushion:
//                              frozen, 2 cm and 5 cm off, pots at several angles,
//                              with the cue raised and kept level.
//   cue_report tables DIR N S  N seeded mid-frame tables (selfplay's RandomFrame) as
//                              table JSON files DIR/table-K.json, for the side-usage
//                              comparison of the script.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "physics/cue/strike.h"
#include "physics/motion/motion.h"
#include "planner/planner.h"
#include "planner/random.h"
#include "planner/selfplay.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

constexpr double kG = 9.81;

void StrikeTables() {
  const physics::BallParams ball;
  const physics::CueParams cue;
  std::printf("### Against TP A.30 (speed and spin from the tip height)\n\n");
  std::printf("Level strike at height b (fraction of R), cue speed 1 m/s. A.30's closed form with the tip's "
              "restitution e: v = (1 + e) V / (1 + m/M + 5/2 b^2), w R / v = 5/2 b.\n\n");
  std::printf("| b | v, e = 1 | A.30 | v, e = %.2f | closed form | w R / v | 5/2 b | largest difference |\n",
              cue.tip_restitution);
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (double b : {0.0, 0.1, 0.2, 0.3, 0.4, 0.5}) {
    physics::CueParams elastic = cue;
    elastic.tip_restitution = 1;
    const physics::CueStrike k{1.0, 0.0, 0.0, b, 0.0};
    const auto e1 = physics::Strike(k, elastic, ball, kG), e = physics::Strike(k, cue, ball, kG);
    const double a30 = 2.0 / (1 + ball.mass / cue.mass + 2.5 * b * b);
    const double closed = (1 + cue.tip_restitution) / (1 + ball.mass / cue.mass + 2.5 * b * b);
    const double spin = e.shot.topspin * ball.radius / e.shot.speed;
    const double diff = std::max({std::abs(e1.shot.speed - a30), std::abs(e.shot.speed - closed), std::abs(spin - 2.5 * b)});
    std::printf("| %.1f | %.6f | %.6f | %.6f | %.6f | %.6f | %.6f | %.1e |\n", b, e1.shot.speed, a30, e.shot.speed,
                closed, spin, 2.5 * b, diff);
  }
  std::printf("\n### Against TP A.31 (squirt) and TP B.1 (measured squirt)\n\n");
  std::printf("Level strike at side b. A.31: squirt = atan(5/2 b sqrt(1 - b^2) / (1 + m/m_e + 5/2 (1 - b^2))). "
              "TP B.1 measured 1.8 deg (low-deflection shaft) and 2.5 deg (standard shaft) at b = 0.45; the end "
              "masses that A.31 needs for them are %.2f g and %.2f g.\n\n",
              1e3 * ball.mass / (2.5 * 0.45 * std::sqrt(1 - 0.2025) / std::tan(physics::DegToRad(1.8)) - 1 - 2.5 * 0.7975),
              1e3 * ball.mass / (2.5 * 0.45 * std::sqrt(1 - 0.2025) / std::tan(physics::DegToRad(2.5)) - 1 - 2.5 * 0.7975));
  std::printf("| side b | 4.5 g shaft, deg | default %.0f g, deg | 7 g shaft, deg | A.31 at the default, deg | "
              "difference |\n|---:|---:|---:|---:|---:|---:|\n",
              cue.end_mass * 1e3);
  for (double b : {0.05, 0.1, 0.2, 0.3, 0.4, 0.45, 0.5}) {
    auto squirt = [&](double end_mass) {
      physics::CueParams c = cue;
      c.end_mass = end_mass;
      return physics::RadToDeg(physics::Strike(physics::CueStrike{1, 0, b, 0, 0}, c, ball, kG).squirt);
    };
    const double a31 = physics::RadToDeg(
        std::atan(2.5 * b * std::sqrt(1 - b * b) / (1 + ball.mass / cue.end_mass + 2.5 * (1 - b * b))));
    std::printf("| %.2f | %.3f | %.3f | %.3f | %.3f | %.1e |\n", b, squirt(0.0045), squirt(cue.end_mass),
                squirt(0.007), a31, std::abs(squirt(cue.end_mass) - a31));
  }
  std::printf("\nAt b = 0.45 the default shaft squirts %.2f deg: inside the measured 1.8-2.5 deg.\n",
              physics::RadToDeg(physics::SquirtAngle(0.45, cue, ball)));

  std::printf("\n### Swerve\n\nA raised cue struck at side b, cue speed 1.2 m/s; the ball's path on the cloth "
              "(closed-form sliding, then rolling). Lateral: how far right of its starting heading the ball is "
              "when it starts to roll, mm (negative: left); turn: its rolling heading less its starting one, deg; "
              "slide: the distance it slid, m.\n\n");
  std::printf("| elevation, deg | side b | squirt, deg | swerve spin, rad/s | lateral, mm | turn, deg | slide, m | "
              "strike |\n|---:|---:|---:|---:|---:|---:|---:|---|\n");
  const physics::ClothParams cloth;
  for (double e : {0.0, 5.0, 10.0, 15.0, 20.0}) {
    for (double b : {0.2, 0.4}) {
      const auto res = physics::Strike(physics::CueStrike{1.2, 0.0, b, 0.0, physics::DegToRad(e)}, cue, ball, kG);
      physics::BallState s = physics::StruckBall(res.shot, Vec2(0, 0));
      s.s = physics::ClassifyMotion(s, ball);
      const double t = physics::TransitionTime(s, ball, cloth);
      const physics::BallState end = physics::Evolve(s, t, ball, cloth);
      const Vec2 h(std::cos(res.shot.heading), std::sin(res.shot.heading));
      const Vec2 right(h.y(), -h.x());
      const double turn = physics::RemainderTwoPi(std::atan2(end.v.y(), end.v.x()) - res.shot.heading);
      std::printf("| %.0f | %.1f | %.2f | %.1f | %.2f | %.2f | %.3f | %s |\n", e, b, physics::RadToDeg(res.squirt),
                  res.shot.swerve_spin, 1e3 * end.r.dot(right), physics::RadToDeg(-turn), end.r.norm(),
                  physics::ToString(res.status));
    }
  }
  std::printf("\n### The miscue and hop limits\n\n");
  std::printf("Miscue: contact offsets beyond sin(atan(%.2f)) = %.3f R (the tip's friction angle). Hop: the "
              "bed takes a raised cue's downward push; at the bed's restitution %.1f the ball would rise "
              "(e v_down)^2 / 2g; strikes that would rise more than %.0f mm are refused. The fastest centre "
              "strike allowed, by elevation:\n\n",
              cue.tip_friction, physics::MiscueLimit(cue), cue.bed_restitution, cue.max_hop * 1e3);
  std::printf("| elevation, deg | fastest cue, m/s | its ball speed, m/s |\n|---:|---:|---:|\n");
  for (double e : {2.0, 5.0, 10.0, 15.0, 20.0, 25.0}) {
    double lo = 0, hi = 10;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      const auto res = physics::Strike(physics::CueStrike{mid, 0, 0, 0, physics::DegToRad(e)}, cue, ball, kG);
      (res.status == physics::StrikeStatus::kOk ? lo : hi) = mid;
    }
    const auto res = physics::Strike(physics::CueStrike{lo, 0, 0, 0, physics::DegToRad(e)}, cue, ball, kG);
    std::printf("| %.0f | %s | %.2f |\n", e, hi >= 10 ? "10 (no limit)" : std::to_string(lo).substr(0, 4).c_str(),
                res.shot.speed);
  }
}

void CushionCases() {
  const physics::TableModel& table = physics::DefaultTable();
  const double c = table.cushion_contact_distance();
  const double y = table.pocket(physics::PocketId::kMiddleRight).mouth_centre.y();
  std::printf("| cue ball | red | best shot | best pot offered: P(pot) | its cue elevation, deg | its tip height | "
              "level cue only: best shot | best pot offered: P(pot) |\n|---|---|---|---:|---:|---:|---|---:|\n");
  for (double gap : {0.0, 0.02, 0.05}) {
    for (double dy : {0.0, -0.13, 0.25}) {
      PlanRequest r;
      r.table.balls = {{BallKind::kCue, Vec2(c + gap, y)}, {BallKind::kRed, Vec2(0.9, y + dy)}};
      r.time_budget = 10;
      r.max_simulations = 20000;
      r.seed = 1;
      r.max_shots = 5;
      auto best_pot = [](const PlanAnswer& a) -> const PlannedShot* {
        for (const PlannedShot& s : a.shots) {
          if (s.kind == ShotKind::kPot) return &s;
        }
        return nullptr;
      };
      auto describe = [](const PlanAnswer& a) {
        if (a.shots.empty()) return std::string("none");
        const PlannedShot& s = a.shots.front();
        std::string d = ToString(s.kind);
        if (s.kind == ShotKind::kPot) d += std::string(" ") + ToString(s.route) + " " + physics::ToString(s.pocket);
        return d;
      };
      const PlanAnswer raised = Planner::Default().Plan(r);
      r.limits.cue.max_elevation = 0;
      const PlanAnswer level = Planner::Default().Plan(r);
      const PlannedShot* pot = best_pot(raised);
      const PlannedShot* level_pot = best_pot(level);
      char p[32] = "none", e[32] = "-", h[32] = "-", lp[32] = "none";
      if (pot != nullptr) {
        std::snprintf(p, sizeof p, "%.2f", pot->pot_probability);
        std::snprintf(e, sizeof e, "%.0f", physics::RadToDeg(pot->cue.elevation));
        std::snprintf(h, sizeof h, "%.2f", pot->cue.height);
      }
      if (level_pot != nullptr) std::snprintf(lp, sizeof lp, "%.2f", level_pot->pot_probability);
      std::printf("| %s | (0.9, %+.2f from the pocket's line) | %s | %s | %s | %s | %s | %s |\n",
                  gap == 0 ? "frozen to the left cushion" : (std::to_string(static_cast<int>(gap * 100)) + " cm off it").c_str(),
                  dy, describe(raised).c_str(), p, e, h, describe(level).c_str(), lp);
    }
  }
}

const char* KindName(BallKind k) {
  switch (k) {
    case BallKind::kCue: return "CUE";
    case BallKind::kRed: return "RED";
    case BallKind::kYellow: return "YELLOW";
    case BallKind::kGreen: return "GREEN";
    case BallKind::kBrown: return "BROWN";
    case BallKind::kBlue: return "BLUE";
    case BallKind::kPink: return "PINK";
    case BallKind::kBlack: return "BLACK";
  }
  return "RED";
}

int Tables(const std::string& dir, int n, std::uint64_t seed) {
  const physics::TableModel& model = physics::DefaultTable();
  for (int k = 0; k < n; ++k) {
    Rng rng(DeriveSeed(seed, static_cast<std::uint64_t>(k)));
    const TableState t = RandomFrame(rng, 6 + k % 5, model);
    std::ofstream out(dir + "/table-" + std::to_string(k) + ".json");
    out << "{\"balls\": [";
    for (size_t i = 0; i < t.balls.size(); ++i) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "%s{\"id\": \"b%zu\", \"kind\": \"%s\", \"position\": {\"x\": %.17g, \"y\": %.17g}}",
                    i ? ", " : "", i, KindName(t.balls[i].kind), t.balls[i].position.x(), t.balls[i].position.y());
      out << buf;
    }
    out << "]}\n";
    if (!out) return 1;
  }
  return 0;
}

}  // namespace
}  // namespace snooker::planner

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "";
  if (what == "strike") {
    snooker::planner::StrikeTables();
    return 0;
  }
  if (what == "cushion") {
    snooker::planner::CushionCases();
    return 0;
  }
  if (what == "tables" && argc == 5) return snooker::planner::Tables(argv[2], std::atoi(argv[3]), std::strtoull(argv[4], nullptr, 10));
  std::fprintf(stderr, "usage: cue_report strike | cushion | tables DIR N SEED\n");
  return 2;
}
