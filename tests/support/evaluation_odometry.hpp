// Test helper: the odometry errors the real-recording evaluation
// re-synthesises odometry with (1.5 % scale, 0.3 deg/m heading drift, 5 mm
// and 0.1 deg of noise per sqrt(m)), and the laser's odometric poses of a
// corrected recording made with them (seeded).
#pragma once

#include <random>
#include <vector>

#include "structloc/map_building/posed_scans.hpp"
#include "structloc/simulation_core/odometry_errors.hpp"

namespace structloc::testing {

inline simulation_core::OdometryErrorModel EvaluationOdometryErrors() {
  simulation_core::OdometryErrorModel errors;
  errors.scale_error = 0.015;
  errors.heading_drift_rad_per_m = 0.3 * geometry::kPi / 180.0;
  errors.noise_xy_m_per_sqrt_m = 0.005;
  errors.noise_theta_rad_per_sqrt_m = 0.1 * geometry::kPi / 180.0;
  return errors;
}

inline std::vector<geometry::Pose2D> EvaluationOdometry(const map_building::PosedScanLog& log,
                                                        unsigned seed) {
  std::mt19937 noise(seed);
  simulation_core::OdometrySynthesiser synthesiser(EvaluationOdometryErrors(), noise,
                                                   log.scans.front().laser_pose);
  std::vector<geometry::Pose2D> odometry;
  for (const auto& scan : log.scans) odometry.push_back(synthesiser.Next(scan.laser_pose));
  return odometry;
}

}  // namespace structloc::testing
