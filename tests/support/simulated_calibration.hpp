// A simulated calibration recording as the calibration issues describe it:
// the scenario's encoders, and fixes of the robot at every scan (0.1 s)
// with 5 mm and 0.0055 rad noise and their variances; the true base poses at
// the fixes inside the encoder recording; and the calibration options whose
// process noise is the simulator's (wheel slip per integration step at
// cruising speed, a tricycle's steering-encoder quantisation as heading noise).
// Shared by the calibration's efficiency evaluation and its benchmark.
#pragma once

#include <random>
#include <string>
#include <vector>

#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc/log_formats/tum_reader.hpp"
#include "structloc/simulation_core/recorder.hpp"
#include "structloc/simulation_core/scenario.hpp"

namespace structloc::testing {

inline constexpr double kFixSigmaXy_m = 0.005;
inline constexpr double kFixSigmaTheta_rad = 0.0055;

struct SimulatedCalibration {
  std::vector<calibration_core::EncoderSample> encoders;
  std::vector<calibration_core::Fix> fixes;
  std::vector<geometry::Pose2D> true_poses;  // base, at the fixes inside the encoder recording
};

// Records `scenario` with `seed` into `dir` and draws the fixes (seeded too).
inline SimulatedCalibration RecordCalibration(simulation_core::Scenario scenario, uint32_t seed,
                                              const std::string& dir) {
  scenario.seed = seed;
  simulation_core::RecordScenario(scenario, dir);
  SimulatedCalibration run;
  run.encoders = calibration_core::ReadEncodersCsv(
      dir + "/encoders.csv", scenario.nominal.traction_counter_bits, scenario.nominal.kind);
  std::mt19937 rng(1000 + seed);
  std::normal_distribution<double> xy(0.0, kFixSigmaXy_m), th(0.0, kFixSigmaTheta_rad);
  for (const auto& p : log_formats::ReadTum(dir + "/truth.tum")) {
    calibration_core::Fix f;
    f.t = p.stamp;
    f.pose = {p.pose.x + xy(rng), p.pose.y + xy(rng), geometry::WrapAngle(p.pose.theta + th(rng))};
    f.has_variance = true;
    f.variance = {kFixSigmaXy_m * kFixSigmaXy_m, kFixSigmaXy_m * kFixSigmaXy_m,
                  kFixSigmaTheta_rad * kFixSigmaTheta_rad};
    run.fixes.push_back(f);
    if (p.stamp >= run.encoders.front().t && p.stamp < run.encoders.back().t) {
      run.true_poses.push_back(p.pose);
    }
  }
  return run;
}

// Calibration options with the simulator's process noise.
inline calibration_core::CalibrationOptions SimulatorNoiseOptions(
    const simulation_core::Scenario& scenario) {
  calibration_core::CalibrationOptions options;
  options.estimate = calibration_core::DefaultEstimate(scenario.nominal.kind);
  const double step_path_m = scenario.path.speed_m_s * scenario.step_s;
  options.slip_variance_m2_per_m =
      scenario.errors.wheel_slip_std * scenario.errors.wheel_slip_std * step_path_m;
  if (scenario.nominal.kind == kinematics::DriveKind::kTricycle) {
    const double q = scenario.nominal.steering_rad_per_tick;
    const double axle = scenario.nominal.axle_distance;
    options.heading_variance_rad2_per_m = q * q / 12.0 * step_path_m / (axle * axle);
  } else {
    options.heading_variance_rad2_per_m = 0.0;  // both wheels slip alike; no steering encoder
  }
  return options;
}

}  // namespace structloc::testing
