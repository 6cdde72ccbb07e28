// Tracked shots made by the simulator: what a vision system would record of a
// table whose physics is `world`, for testing that a fit finds `world` again and
// for sim-to-real experiments (a planner tuned on one model, played on another).
//
// Each shot, from a seeded generator (the same seed gives the same shots on every
// machine: the generator and its Gaussian are this library's own, not the
// standard library's, whose distributions differ between implementations):
//  * the scene: the cue ball anywhere at least kSceneMargin from the cushion noses,
//    an object ball 0.25-1.0 m from it, and with probability two_object_fraction a
//    second object ball anywhere clear of both (3R between centres);
//  * the strike, in the cue's terms: cue speed uniform in [min_cue_speed,
//    max_cue_speed], tip offsets uniform over the disc of tip_reach times the
//    world cue's miscue limit (side included), elevation uniform in [0,
//    max_elevation]. With probability aimed_fraction the cue ball is aimed at a
//    cut uniform in [-max_cut, max_cut] on the first object ball (the world's own
//    squirt allowed for, so most shots are cut shots with ball-ball contact);
//    otherwise at a uniform heading (cushion-first shots, some misses);
//  * the run in `world` (options.numerics), sighted every sighting_interval from
//    then until the first sighting after every ball rests (the interval grows for
//    runs that would have more than max_sightings), each seen coordinate with
//    Gaussian noise of vision_noise_m; a ball is NaN from the time it drops. With
//    noisy_start the recorded starting positions carry the same noise (the run
//    itself starts from the true ones), as one frame of a vision system's would.
//    Off by default: a fit takes the starting positions as exact, and a
//    collision turns a millimetre there into centimetres later (a 1 mm error of
//    the ghost ball turns the object ball by about 1 / (2R) = 2 deg), so that
//    with 1 mm on the starts the fits of the cue and of the ball-ball law miss
//    (measured: end_mass 8.4 g for 9 g). Real starting positions want averaging
//    over many frames of the balls at rest.
// A strike the world's cue refuses (a hop) or a run that ends on a cap is drawn
// again (at most kMaxDraws times per shot).
#pragma once

#include <cstdint>
#include <vector>

#include "calibration/observations.h"
#include "calibration/predict.h"
#include "physics/model/model.h"

namespace snooker::calibration {

struct RecordOptions {
  double min_cue_speed = 0.5;  ///< m/s
  double max_cue_speed = 4.0;  ///< m/s
  /// Tip offsets within this fraction of the miscue limit.
  double tip_reach = 0.9;
  double max_elevation = 5.0 * physics::kPi / 180;  ///< rad
  double max_cut = 60.0 * physics::kPi / 180;       ///< rad
  double aimed_fraction = 0.85;
  double two_object_fraction = 0.4;
  double sighting_interval = 0.1;  ///< s
  int max_sightings = 150;
  bool noisy_start = false;
  physics::SimParams numerics = CalibrationNumerics();
};

/// Distance of every starting ball from the cushion noses, m.
inline constexpr double kSceneMargin = 0.1;
/// Draws per shot before Record gives up (std::runtime_error).
inline constexpr int kMaxDraws = 100;
/// Most shots one call records.
inline constexpr int kMaxRecordedShots = 100000;

/// `shots` tracked shots of the table `world` (above). Throws std::invalid_argument
/// naming the bad value for shots outside [0, kMaxRecordedShots], a noise that is
/// negative or not finite, options out of range or a world that fails
/// ValidateModel.
std::vector<TrackedShot> Record(const physics::Model& world, int shots, std::uint64_t seed,
                                double vision_noise_m, const RecordOptions& options = {});

}  // namespace snooker::calibration
