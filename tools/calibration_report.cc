// The measurements behind docs/calibration.md (scripts/calibration-report), each
// printed as one JSON document:
//   calibration_report throw FITTED.json    the fitted throw law against the data and
//                                           across cuts and speeds, beside the default
//   calibration_report cushion              the cushion group fitted to the measured
//                                           rebound fit on this table's nose
//   calibration_report identify             fits of data made by the simulator with
//                                           known parameters, per group
// Seeded: the same build prints the same numbers.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "calibration/datasets.h"
#include "calibration/fit.h"
#include "calibration/predict.h"
#include "calibration/record.h"
#include "cli/model_file.h"
#include "physics/core/types.h"

namespace {

using namespace snooker;
using calibration::FitResult;
using calibration::Group;
using calibration::Observations;

constexpr double kR = 0.02625;

std::string Num(double x) {
  if (!std::isfinite(x)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

double ThrowDeg(const physics::Model& m, double cut_deg, double object_speed) {
  calibration::ThrowObservation o;
  o.cut = physics::DegToRad(cut_deg);
  o.object_ball_speed = object_speed;
  const calibration::ThrowPrediction p = calibration::PredictThrow(o, m);
  return p.error.empty() ? physics::RadToDeg(p.throw_angle) : NAN;
}

int Throw(const std::string& fitted_path) {
  physics::Model fitted;
  if (std::string e = cli::LoadModelFile(fitted_path, &fitted); !e.empty()) {
    std::cerr << e << "\n";
    return 2;
  }
  const physics::Model plain;
  std::ostringstream out;
  out << "{\"points\": [";
  bool first = true;
  for (const calibration::ThrowObservation& t : calibration::AlciatoreStunThrow45()) {
    out << (first ? "" : ", ") << "{\"speed\": " << Num(*t.object_ball_speed)
        << ", \"measured\": " << Num(physics::RadToDeg(t.measured_throw))
        << ", \"default\": " << Num(ThrowDeg(plain, 45, *t.object_ball_speed))
        << ", \"fitted\": " << Num(ThrowDeg(fitted, 45, *t.object_ball_speed)) << "}";
    first = false;
  }
  out << "], \"grid\": [";
  first = true;
  for (double cut : {20.0, 30.0, 45.0, 60.0}) {
    for (double v : {0.25, 0.35, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.5, 3.0}) {
      out << (first ? "" : ", ") << "{\"cut\": " << Num(cut) << ", \"speed\": " << Num(v)
          << ", \"default\": " << Num(ThrowDeg(plain, cut, v)) << ", \"fitted\": " << Num(ThrowDeg(fitted, cut, v))
          << "}";
      first = false;
    }
  }
  // The no-slip bound on a stun shot's throw: friction stops the slip at the contact
  // (both balls' surfaces geared), tan(throw) = 2 tan(cut) / (7 (1 + e)).
  out << "], \"gear_limit\": [";
  first = true;
  for (double cut : {20.0, 30.0, 45.0, 60.0}) {
    const double e = fitted.ball_ball.e;
    out << (first ? "" : ", ") << "{\"cut\": " << Num(cut) << ", \"limit\": "
        << Num(physics::RadToDeg(std::atan(2 * std::tan(physics::DegToRad(cut)) / (7 * (1 + e))))) << "}";
    first = false;
  }
  out << "]}\n";
  std::cout << out.str();
  return 0;
}

void PrintFit(std::ostream& out, const FitResult& r) {
  out << "{\"error\": \"" << r.error << "\", \"status\": \"" << r.status << "\", \"evaluations\": " << r.evaluations
      << ", \"seconds\": " << Num(r.seconds) << ", \"chi2\": " << Num(r.reduced_chi_square) << ", \"parameters\": [";
  for (std::size_t k = 0; k < r.parameters.size(); ++k) {
    const calibration::ParameterEstimate& p = r.parameters[k];
    out << (k ? ", " : "") << "{\"name\": \"" << p.name << "\", \"start\": " << Num(p.start)
        << ", \"fitted\": " << Num(p.fitted) << ", \"sigma\": " << Num(p.uncertainty) << "}";
  }
  auto kind = [&](const char* name, const calibration::KindResiduals& k) {
    out << ", \"" << name << "\": {\"count\": " << k.count << ", \"before\": " << Num(k.rms_before)
        << ", \"after\": " << Num(k.rms_after) << "}";
  };
  out << "]";
  kind("throw_deg", r.throw_deg);
  kind("rebound_speed", r.rebound_speed);
  kind("rebound_angle_deg", r.rebound_angle_deg);
  kind("position", r.position);
  out << "}";
}

// Rebounds of a rolling ball square on at the measured fit of Mathavan et al.
// (2009): v_out = -0.0877 v^2 + 1.131 v - 0.0953, v in 0.28-3.5 m/s.
int Cushion() {
  Observations o;
  for (double v = 0.3; v <= 3.5 + 1e-9; v += 0.2) {
    calibration::CushionObservation c;
    c.speed = v;
    c.angle = physics::kPi / 2;
    c.topspin = v / kR;
    c.rebound_speed = -0.0877 * v * v + 1.131 * v - 0.0953;
    o.rebounds.push_back(c);
  }
  const Group groups[] = {Group::kCushion};
  calibration::FitOptions options;
  options.rebound_speed_sigma = 0.01;
  const physics::Model start;
  const FitResult r = calibration::Fit(o, groups, start, options);
  std::ostringstream out;
  out << "{\"fit\": ";
  PrintFit(out, r);
  out << ", \"rebounds\": [";
  for (std::size_t i = 0; i < o.rebounds.size(); ++i) {
    const calibration::CushionObservation& c = o.rebounds[i];
    out << (i ? ", " : "") << "{\"speed\": " << Num(c.speed) << ", \"measured\": " << Num(c.rebound_speed)
        << ", \"default\": " << Num(calibration::PredictRebound(c, start).speed)
        << ", \"fitted\": " << Num(calibration::PredictRebound(c, r.model).speed) << "}";
  }
  out << "], \"knots\": [";
  const physics::RestitutionCurve& a = start.cushion.restitution_curve;
  const physics::RestitutionCurve& b = r.model.cushion.restitution_curve;
  for (int k = 0; k < a.points; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    out << (k ? ", " : "") << "{\"speed\": " << Num(a.speed[i]) << ", \"default\": " << Num(a.e[i])
        << ", \"fitted\": " << Num(b.e[i]) << "}";
  }
  out << "]}\n";
  std::cout << out.str();
  return 0;
}

physics::Model WithLaw(double a, double b, double c) {
  physics::Model m;
  m.ball_ball = physics::WithFrictionCurve(m.ball_ball, {a, b, c});
  return m;
}

struct Case {
  const char* name;
  const char* data;
  Group group;
  physics::Model world;
  std::vector<std::pair<const char*, double>> truth;
};

// Throws over cuts, speeds and spins of `world`, with 0.1 deg of noise.
Observations ThrowsOf(const physics::Model& world, std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0, physics::DegToRad(0.1));
  Observations o;
  for (double cut : {15.0, 30.0, 45.0, 60.0, 75.0}) {
    for (double v : {0.4, 0.8, 1.5, 2.5}) {
      for (double roll : {0.0, 1.0}) {
        calibration::ThrowObservation t;
        t.cut = physics::DegToRad(cut);
        t.cue_ball_speed = v;
        t.topspin = roll * v / kR;
        t.measured_throw = calibration::PredictThrow(t, world).throw_angle + noise(rng);
        o.throws.push_back(t);
      }
    }
  }
  return o;
}

int Identify() {
  physics::Model cloth;
  cloth.cloth.mu_s = 0.24;
  cloth.cloth.mu_r = 0.015;
  cloth.cloth.spin_decel = 18;
  physics::Model cue;
  cue.cue.end_mass = 0.009;
  cue.cue.tip_restitution = 0.78;
  const physics::Model law = WithLaw(0.01, 0.12, 0.8);
  const std::vector<Case> cases = {
      {"ball-ball", "40 throws, 0.1 deg of noise", Group::kBallBall, law,
       {{"ball_ball.mu_bb", 0.01}, {"ball_ball.slip_gain", 0.12}, {"ball_ball.slip_decay", 0.8}}},
      {"ball-ball", "50 tracked shots, 1 mm of noise", Group::kBallBall, law,
       {{"ball_ball.mu_bb", 0.01}, {"ball_ball.slip_gain", 0.12}, {"ball_ball.slip_decay", 0.8}}},
      {"cloth", "50 tracked shots, 1 mm of noise", Group::kCloth, cloth,
       {{"cloth.mu_s", 0.24}, {"cloth.mu_r", 0.015}, {"cloth.spin_decel", 18}}},
      {"cloth", "50 tracked shots, 0.5 mm of noise", Group::kCloth, cloth,
       {{"cloth.mu_s", 0.24}, {"cloth.mu_r", 0.015}, {"cloth.spin_decel", 18}}},
      {"cue", "50 tracked shots, 1 mm of noise", Group::kCue, cue,
       {{"cue.end_mass", 0.009}, {"cue.tip_restitution", 0.78}}},
  };
  std::ostringstream out;
  out << "[";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    std::mt19937_64 rng(11 + i);
    const bool throws = std::string(c.data).find("throws") != std::string::npos;
    const double noise = std::string(c.data).find("0.5 mm") != std::string::npos ? 0.5e-3 : 1e-3;
    Observations o;
    if (throws) {
      o = ThrowsOf(c.world, rng);
    } else {
      o.shots = calibration::Record(c.world, 50, 100 + i, noise);
    }
    calibration::FitOptions options;
    if (throws) options.throw_sigma = physics::DegToRad(0.1);
    options.position_sigma = noise;
    const Group groups[] = {c.group};
    const FitResult r = calibration::Fit(o, groups, physics::Model{}, options);
    out << (i ? ", " : "") << "{\"group\": \"" << c.name << "\", \"data\": \"" << c.data << "\", \"truth\": {";
    for (std::size_t k = 0; k < c.truth.size(); ++k) {
      out << (k ? ", " : "") << "\"" << c.truth[k].first << "\": " << Num(c.truth[k].second);
    }
    out << "}, \"fit\": ";
    PrintFit(out, r);
    out << "}";
  }
  out << "]\n";
  std::cout << out.str();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "";
  if (what == "throw" && argc == 3) return Throw(argv[2]);
  if (what == "cushion") return Cushion();
  if (what == "identify") return Identify();
  std::cerr << "usage: calibration_report throw FITTED.json | cushion | identify\n";
  return 2;
}
