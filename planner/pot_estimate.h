// The fast pot-probability estimate: how likely a pot is to drop under the robot's
// execution noise and the vision system's position noise, from the geometry alone.
//
// To first order every error moves the object ball's line sideways at the mouth by
//   dlat = L dtheta + n_perp . dO,     dtheta = dh + dc,
//   dc = db / (2R cos c),  db = -dh (u . (O - C)) + u_perp . (dO - dC)
// (heading h along u, cut c, object ball O sent along n over L to the mouth, cue
// ball C, impact parameter b = 2R sin c; the ghost-ball geometry). With independent
// Gaussian errors - heading sigma_h, each ball's position sigma per axis, and the
// throw that spin and speed noise add (ThrowModel) - the lateral error is Gaussian:
//   sigma^2 = sigma_h^2 L^2 (1 - u.(O-C) / (2R cos c))^2 + sigma_C^2 k^2
//           + sigma_O^2 (k^2 + 1 + 2k cos c) + L^2 sigma_throw^2,   k = L / (2R cos c),
// and the pot drops when the line falls inside the pocket's window (PocketModel):
//   P = Phi((hi - mu) / sigma) - Phi((lo - mu) / sigma),
// mu being the line's planned offset. For a straight pot 1 m from the pocket, 0.2 mm
// of vision error on each ball moves the line by about 5.5 mm at the mouth; 0.02 deg
// of heading by about 1.6 mm with the cue ball 0.3 m back and 6 mm from 1 m back.
// tests/planner/pot_estimate_test.cc checks it against Monte Carlo with the simulator.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "physics/core/types.h"
#include "physics/table/table.h"
#include "physics/cue/strike.h"
#include "planner/geometry.h"
#include "planner/pocket_model.h"
#include "planner/throw_model.h"

namespace snooker::planner {

/// Standard deviations of the robot's execution, of the model and of vision (all
/// independent, Gaussian, zero mean). The execution is the robot's cue (its aim,
/// speed, tip placement and elevation, struck through physics/cue/strike.h); the
/// model's uncertainty is the squirt and the throw a real table gives, each a
/// fraction of the model's. Defaults and their reasons: docs/cue.md.
struct NoiseModel {
  /// The cue's aim (its heading), rad: a robot's pointing repeatability.
  double aim = 0.02 * physics::kPi / 180;
  /// The cue's speed, as a fraction of the speed.
  double cue_speed_fraction = 0.01;
  /// Where the tip meets the ball, per axis (across and up), m: the end effector's
  /// placement at the tip.
  double tip_offset = 0.1e-3;
  /// The cue's elevation, rad.
  double elevation = 0.1 * physics::kPi / 180;
  /// The squirt, as a fraction of the model's (the shaft's end mass is known to
  /// about this), and the throw of ball-ball impacts, as a fraction of the model's
  /// (cloth, chalk and ball condition move it).
  double squirt_fraction = 0.15;
  double throw_fraction = 0.10;
  /// More noise on the cue ball itself after the strike, for a client that models
  /// its own execution in those terms: heading, rad; speed, fraction; topspin and
  /// sidespin, rad/s. Zero by default.
  double heading = 0;
  double speed_fraction = 0;
  double topspin = 0;
  double sidespin = 0;
  /// Vision: each ball centre, per axis, m (the API's default for every ball).
  double position = 0.2e-3;
};

/// NoiseModel's defaults for a simulated world that is the model itself (self-play,
/// matches): the cue's noise, and no model uncertainty (the planner is told the
/// truth: there, squirt and throw are exactly the model's).
inline NoiseModel ModelWorldNoise() {
  NoiseModel n;
  n.squirt_fraction = 0;
  n.throw_fraction = 0;
  return n;
}

/// The noise of the cue ball just after the strike, in the terms of the fast
/// estimates (heading, speed, topspin, sidespin): `noise`'s own terms plus what the
/// cue's noise gives a centre-ball strike at `speed` (m/s): the aim and the squirt
/// of an offset error in heading, the offset errors' spin (5/2 v dx / R^2), the cue
/// speed's error in speed. The other terms of `noise` are kept.
NoiseModel BallTermsNoise(const NoiseModel& noise, const physics::CueParams& cue, const physics::BallParams& ball,
                          double speed);

/// Standard normal cumulative distribution.
double NormalCdf(double x);

/// Probability that a Gaussian offset (mean `mean`, sigma `sigma`, m) falls in the window.
double WindowProbability(double mean, double sigma, const PocketWindow& window);

/// How far the object ball's line moves sideways at the mouth per radian of the cue
/// ball's heading (m/rad, its magnitude): the heading term of LateralSigma. Any error
/// that turns the cue ball's heading acts through it, the squirt's among them.
double HeadingGain(const physics::Vec2& cue, const physics::Vec2& object, double heading, double cut,
                   double distance, double radius);

/// The sideways spread at the mouth (m) that the model's squirt adds to a stroke
/// whose squirt is `squirt` (rad): the squirt known to noise.squirt_fraction of
/// itself, a heading error of that fraction of it, through `heading_gain` (m/rad).
double SquirtSigma(double squirt, double heading_gain, const NoiseModel& noise);

/// The sideways spread at the mouth (m) that the model's throw adds to a line thrown
/// by `throw_angle` (rad) that runs `distance` (m) to the mouth: the throw known to
/// noise.throw_fraction of itself.
double ThrowSigma(double throw_angle, double distance, const NoiseModel& noise);

/// Lateral standard deviation at the mouth (m) of the object ball's line for a pot
/// from cue ball `cue` (position sigma `cue_sigma`) onto `object` (`object_sigma`)
/// along `heading` with cut `cut`, the object ball travelling `distance` (m) to the
/// mouth; `contact_speed` (m/s) selects the throw sensitivities.
double LateralSigma(const physics::Vec2& cue, const physics::Vec2& object, double heading,
                    double cut, double distance, double contact_speed, double cue_sigma,
                    double object_sigma, const NoiseModel& noise, const ThrowModel& throws,
                    double radius);

/// A pot judged from the geometry alone, aimed at the centre of the pocket's window.
struct PotEstimate {
  GhostAim aim;                  ///< cut, heading, ghost-ball position
  double object_direction = 0;   ///< rad
  double distance = 0;           ///< object ball to the mouth, m
  double approach = 0;           ///< angle from the pocket's axis, rad
  PocketWindow window;           ///< at the assumed arrival speed
  double sigma = 0;              ///< lateral, m
  /// Another route's HeadingGain (m/rad): its first ball's gain through the
  /// route's levers (routes.h), set from the route's candidate. A direct pot leaves
  /// it 0: the search takes its gain from the stroke's own simulated line.
  double heading_gain = 0;
  double probability = 0;
};

/// The speed (m/s) at which a planned pot is assumed to reach the mouth when its
/// actual speed is not known yet (the next shot of a position).
inline constexpr double kTypicalArrivalSpeed = 0.5;

/// Typical speed of the cue ball at contact for a pot over `distance` (m) with cut
/// `cut` (rad): enough to bring the object ball to the mouth at kTypicalArrivalSpeed. m/s.
double TypicalContactSpeed(double distance, double cut);

/// A ball's straight line into a pocket aimed at the centre of the pocket's window
/// (the line whose offset at the mouth is the window's centre; the window depends
/// on the direction, so it is settled in two passes).
struct PocketLine {
  double direction = 0;  ///< rad, table frame
  PocketWindow window;   ///< at the arrival speed asked for
  double distance = 0;   ///< from the ball to the mouth along the line, m
};

/// The line of a ball at `from` into `pocket`, or nullopt when the pocket is closed
/// to it (an empty window) or the window's centre is out of its reach.
std::optional<PocketLine> LineIntoPocket(const PocketModel& pockets, const physics::Vec2& from,
                                         physics::PocketId pocket, double arrival_speed = kTypicalArrivalSpeed);

/// Lines into pockets remembered by all they depend on: the pocket model, the ball's
/// position, the pocket and the arrival speed, compared exactly, so that a hit is the
/// very line LineIntoPocket would give. A position valued again with the same object
/// balls (the spread's two sides, the placements of a cue ball in hand, the search's
/// next stroke, which moved few of them) then skips their lines' work. Eight ways in
/// each of 32 sets, the oldest line of a full set giving way: a table's lines (six
/// pockets for each of its balls) then share a set only eight at a time, which no
/// hash makes likely. A set keeps its keys' hashes in a row of their own, so that a
/// look-up compares one cache line before it reads an entry. Fixed size, no
/// allocation; one per thread (it is written on every look-up).
class PocketLineCache {
 public:
  std::optional<PocketLine> Line(const PocketModel& pockets, const physics::Vec2& from,
                                 physics::PocketId pocket, double arrival_speed = kTypicalArrivalSpeed);
  /// Look-ups answered from the cache, and worked out, since construction.
  std::int64_t hits() const { return hits_; }
  std::int64_t misses() const { return misses_; }

 private:
  static constexpr int kSetBits = 5;
  static constexpr int kWays = 8;
  struct Entry {
    std::uint64_t model = 0;  // PocketModel::serial(); 0: empty
    double x = 0, y = 0, speed = 0;
    int pocket = -1;
    std::optional<PocketLine> line;
  };
  struct Set {
    std::array<std::uint64_t, kWays> hashes{};  // of the ways' keys; a match is then checked
    std::array<Entry, kWays> ways{};
    int next = 0;  // the way the next new line takes
  };
  std::array<Set, std::size_t{1} << kSetBits> sets_{};
  std::int64_t hits_ = 0;
  std::int64_t misses_ = 0;
};

/// The estimate for potting `object` into `pocket` from `cue`, or nullopt when the
/// pocket cannot be reached at that angle or the cut is 90 deg or more. Only the
/// geometry of the three points: paths blocked by other balls are the caller's.
std::optional<PotEstimate> EstimatePot(const physics::Vec2& cue, const physics::Vec2& object,
                                       physics::PocketId pocket, double cue_sigma,
                                       double object_sigma, const NoiseModel& noise,
                                       const PocketModel& pockets, const ThrowModel& throws,
                                       double arrival_speed = kTypicalArrivalSpeed);

/// The same estimate along `line`, the object ball's LineIntoPocket (or a cache's).
std::optional<PotEstimate> EstimatePotAlong(const PocketLine& line, const physics::Vec2& cue,
                                            const physics::Vec2& object, physics::PocketId pocket,
                                            double cue_sigma, double object_sigma, const NoiseModel& noise,
                                            const PocketModel& pockets, const ThrowModel& throws);

}  // namespace snooker::planner
