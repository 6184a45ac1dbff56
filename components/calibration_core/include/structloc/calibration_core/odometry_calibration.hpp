// Odometry calibration (thesis 6.5.4, done properly): re-run the
// tricycle dead reckoning (EQ 46-48) from recorded encoder values for
// candidate parameters and find those that best explain the relative motion
// between consecutive position fixes (so one bad fix cannot poison the rest):
// Levenberg-Marquardt on weighted residuals (fix covariances, or default
// sigmas), Huber-robust against outlier fixes. Parameters: wheel radius, axle
// distance, steering offset, optionally the steering gain (rad per tick) and
// the fix sensor's mounting pose. Reports standard deviations, correlations,
// residual RMS before and after, and refuses to give a number for a parameter
// the trajectory cannot determine. DDS-free. Its parts: calibration_problem
// (intervals and residuals), levenberg_marquardt (the solver),
// observability_pruning and calibration_report_builder.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/kinematics/robot_parameters.hpp"

namespace structloc::calibration_core {

enum Parameter {
  kWheelRadius,
  kAxleDistance,
  kSteeringOffset,
  kSteeringGain,
  kSensorX,
  kSensorY,
  kSensorTheta,
  kParameterCount
};
const char* ParameterName(Parameter p);
const char* ParameterUnit(Parameter p);

struct CalibrationOptions {
  // Which parameters to estimate (the rest stay at their nominal values).
  std::array<bool, kParameterCount> estimate{true, true, true, false, false, false, false};
  double default_sigma_xy_m = 0.01;  // fix noise when fixes.csv has no variances
  double default_sigma_theta_rad = 0.01;
  double min_fix_travel_m = 0.2;  // consecutive used fixes at least this far apart...
  double min_fix_turn_rad = 0.1;  // ... or this much turned
  double huber_k = 3.0;           // robust loss threshold, in standard deviations
  int max_iterations = 50;
  double max_encoder_gap_s = 0.5;  // intervals across longer encoder gaps are skipped
  // A parameter whose standard deviation exceeds this (in its unit) is "not
  // observable" from the trajectory: reported as such and kept at nominal.
  std::array<double, kParameterCount> max_std{0.002, 0.02, 0.0175, 0.00005, 0.1, 0.1, 0.05};
  // The estimate fails when more than this fraction of the fix intervals are
  // outliers (the model does not explain the data)...
  double max_outlier_fraction = 0.5;
  // ... or when its open-loop dead-reckoning RMS against the fixes is above
  // this times the nominal parameters' (1 = it must not be worse; equal is a
  // robot that was calibrated already).
  double max_dead_reckoning_ratio = 1.0;
  // ... or when, with the nominal parameters, one encoder step moves the wheel
  // faster than this (over at least 0.05 s): a counter that wraps at fewer
  // bits than traction_counter_bits, wrong ticks per revolution, a corrupt row.
  double max_wheel_speed_m_s = 20.0;
  // Throws std::invalid_argument (also when no parameter is to be estimated).
  void Validate() const;
};

struct CalibrationReport {
  kinematics::RobotParameters parameters;  // calibrated (nominal where not estimated)
  std::array<double, kParameterCount> standard_deviation{};  // 0 where not estimated
  std::array<bool, kParameterCount> estimated{};
  Eigen::MatrixXd correlation;       // among the estimated parameters, in order
  double residual_rms_before = 0.0;  // weighted (unitless), nominal parameters
  double residual_rms_after = 0.0;
  size_t intervals_used = 0;
  size_t intervals_downweighted = 0;  // outliers (robust weight < 0.5)
  size_t intervals_skipped = 0;       // across encoder gaps or outside the encoder span
  size_t encoder_gaps = 0;
  int iterations = 0;
  // Open-loop dead reckoning RMS against the fixes (DeadReckoningRms); 0 when
  // the estimate failed before it was checked.
  double dead_reckoning_rms_nominal = 0.0;
  double dead_reckoning_rms_calibrated = 0.0;
  std::vector<std::string> warnings;
  // True only for a usable estimate: plausible encoder steps, at least one
  // parameter estimated, finite residuals, at most max_outlier_fraction
  // outliers, plausible values and better dead reckoning than nominal. Otherwise `failure` says
  // which test failed and `likely_causes` what in the inputs probably caused it.
  bool success = false;
  std::string failure;
  std::vector<std::string> likely_causes;
};

// Parses a comma-separated list of parameter names (--estimate); throws
// config::ConfigError for an empty list, an empty item or an unknown name.
std::array<bool, kParameterCount> ParseParameterList(const std::string& list);

// Throws std::invalid_argument on unusable input (too few fixes inside the
// encoder time span, traction ticks beyond the counter width, invalid options
// or nominal parameters). A meaningless estimate is not thrown but reported
// with success == false.
CalibrationReport Calibrate(const std::vector<EncoderSample>& encoders,
                            const std::vector<Fix>& fixes,
                            const kinematics::RobotParameters& nominal,
                            const CalibrationOptions& options);

// Open-loop dead reckoning of the fix sensor over the fixes inside the encoder
// recording, started at the first of them: RMS position error against those
// fixes (how far odometry alone drifts); 0 when no fix is inside.
double DeadReckoningRms(const std::vector<EncoderSample>& encoders, const std::vector<Fix>& fixes,
                        const kinematics::RobotParameters& parameters);

// Which manoeuvres make which parameters observable, for users planning a recording.
std::string TrajectoryAdvice();

}  // namespace structloc::calibration_core
