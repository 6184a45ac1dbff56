// Odometry re-synthesised from a trajectory of known poses (a SLAM-corrected
// recording) with the errors real wheel odometry has: a scale error (wrong
// wheel radius), a heading drift per metre (wrong axle distance, steering
// offset), random noise growing with the distance travelled, and a turn
// scale error and random heading noise growing with the turn (wheels
// slipping as the robot turns), so that a localiser can be evaluated on real
// scans with realistic, documented odometry.
// Zero errors give the known poses back (perfect odometry). DDS-free;
// randomness from the injected generator.
#pragma once

#include <random>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::simulation_core {

struct OdometryErrorModel {
  double scale_error = 0.0;                   // distance travelled is scaled by (1 + this)
  double heading_drift_rad_per_m = 0.0;       // heading error added per metre travelled
  double noise_xy_m_per_sqrt_m = 0.0;         // random translation error, 1 sigma per sqrt(metre)
  double noise_theta_rad_per_sqrt_m = 0.0;    // random heading error, 1 sigma per sqrt(metre)
  double turn_scale_error = 0.0;              // each turn is scaled by (1 + this)
  double noise_theta_rad_per_sqrt_rad = 0.0;  // random heading error, rad per sqrt(rad) turned
  // Throws std::invalid_argument naming the field when a value is not finite,
  // a noise is negative or a scale error is at or below -1.
  void Validate() const;
};

class OdometrySynthesiser {
 public:
  // The odometry starts at `start` (usually the first known pose).
  OdometrySynthesiser(const OdometryErrorModel& model, std::mt19937& rng,
                      const geometry::Pose2D& start);

  // The odometry pose for the next known pose: the motion since the previous
  // known pose, in the robot frame, with the model's errors, added to the
  // previous odometry pose.
  geometry::Pose2D Next(const geometry::Pose2D& known);

 private:
  OdometryErrorModel model_;
  std::mt19937& rng_;
  std::normal_distribution<double> unit_{0.0, 1.0};
  geometry::Pose2D previous_known_;
  geometry::Pose2D odometry_;
};

// A time for a pose reached from `from` at no more than `speed_m_s` and
// `turn_rate_rad_s` and at least `min_step_s` after `previous_stamp`: for logs
// whose own stamps are unusable as motion times (the Intel key scans).
double RestampedTime(double previous_stamp, const geometry::Pose2D& from,
                     const geometry::Pose2D& to, double speed_m_s, double turn_rate_rad_s,
                     double min_step_s);

}  // namespace structloc::simulation_core
