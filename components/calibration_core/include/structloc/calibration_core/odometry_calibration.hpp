// Odometry calibration (thesis 6.5.4, using every fix): re-run the tricycle
// dead reckoning (EQ 46-48) from recorded encoder values for candidate
// parameters inside one batch least-squares problem over the robot's pose at
// every fix time and the parameters: each fix measures its pose, the encoder
// motion between consecutive fixes links neighbouring poses with a process
// noise growing with the distance driven. Sparse robust Levenberg-Marquardt
// (Huber on every fix and interval, so one bad fix cannot poison the rest).
// Parameters: wheel radius, axle distance, steering offset, optionally the
// steering gain (rad per tick) and the fix sensor's mounting pose. Reports
// standard deviations, correlations, what the trajectory's information does
// and does not determine, and refuses to give a number for a parameter the
// trajectory cannot determine. DDS-free. Its parts: calibration_problem (the
// batch problem), batch_solver, observability_pruning, information_statement
// and calibration_report_builder.
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
  kLeftWheelRadius,  // differential drive
  kRightWheelRadius,
  kWheelSeparation,
  kParameterCount
};
const char* ParameterName(Parameter p);
const char* ParameterUnit(Parameter p);
// Lengths and gains, stated relative to their value (their ratios are what a
// trajectory determines); offsets and the mounting are stated in their unit.
bool IsScale(Parameter p);
// Whether `p` is a parameter of a robot of `kind` (the sensor mounting is of both).
bool AppliesTo(Parameter p, kinematics::DriveKind kind);
// The parameters estimated unless the user says otherwise: wheel radius, axle
// distance and steering offset of a tricycle; both wheel radii and the wheel
// separation of a differential drive (the UMBmark parameters).
std::array<bool, kParameterCount> DefaultEstimate(kinematics::DriveKind kind);

struct CalibrationOptions {
  // Which parameters to estimate (the rest stay at their nominal values); only
  // parameters of the robot's drive kind (default: the tricycle's three; see
  // DefaultEstimate).
  std::array<bool, kParameterCount> estimate{true,  true,  true,  false, false,
                                             false, false, false, false, false};
  double default_sigma_xy_m = 0.01;  // fix noise when fixes.csv has no variances
  double default_sigma_theta_rad = 0.01;
  // The coarse start (relative motion between fixes, poses held at the
  // fixes) uses fixes at least this far apart or this much turned.
  double min_fix_travel_m = 0.2;
  double min_fix_turn_rad = 0.1;
  // Process noise of the encoder motion between fixes, per metre the wheel
  // rolls: wheel slip stretches or shrinks each arc (variance of the distance
  // error, m^2 per m), heading noise turns it (rad^2 per m). The tick
  // quantisation at both ends of an interval is added from the robot file.
  double slip_variance_m2_per_m = 1e-6;
  double heading_variance_rad2_per_m = 1e-6;
  double huber_k = 3.0;  // robust loss threshold, in standard deviations
  int max_iterations = 200;
  double max_encoder_gap_s = 0.5;  // intervals across longer encoder gaps are skipped
  // A parameter whose standard deviation exceeds this (in its unit) is "not
  // observable" from the trajectory: reported as such and kept at nominal.
  std::array<double, kParameterCount> max_std{0.002, 0.02, 0.0175, 0.00005, 0.1,
                                              0.1,   0.05, 0.002,  0.002,   0.02};
  // The estimate fails when more than this fraction of the fix intervals are
  // outliers (the model does not explain the data)...
  double max_outlier_fraction = 0.5;
  // ... or when its open-loop dead-reckoning RMS against the fixes is above
  // this times the nominal parameters' (1 = it must not be worse; equal is a
  // robot that was calibrated already).
  double max_dead_reckoning_ratio = 1.0;
  // ... by more than this fraction (re-calibrating a calibrated robot moves
  // its parameters within their uncertainty, and its open-loop drift with them).
  double dead_reckoning_tolerance = 0.02;
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
  Eigen::MatrixXd covariance;   // of the estimated parameters, in Parameter order
  Eigen::MatrixXd correlation;  // among the estimated parameters, in order
  // RMS of the whitened relative motion between fixes at least
  // min_fix_travel_m or min_fix_turn_rad apart (each with both fixes' noise),
  // re-run with the nominal and with the calibrated parameters.
  double residual_rms_before = 0.0;
  double residual_rms_after = 0.0;
  size_t fixes_used = 0;              // inside the encoder recording
  size_t fixes_downweighted = 0;      // outliers (robust weight < 0.5)
  size_t intervals_used = 0;          // encoder motion between consecutive fixes
  size_t intervals_downweighted = 0;  // outliers (robust weight < 0.5)
  size_t intervals_skipped = 0;       // across encoder gaps or outside the encoder span
  size_t encoder_gaps = 0;
  int iterations = 0;
  // Open-loop dead reckoning RMS against the fixes (DeadReckoningRms); 0 when
  // the estimate failed before it was checked.
  double dead_reckoning_rms_nominal = 0.0;
  double dead_reckoning_rms_calibrated = 0.0;
  // What the trajectory determines: the estimated parameters' information
  // in words (best and least determined combinations).
  std::vector<std::string> observability;
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

// The Cramer-Rao bound of the calibration model: the covariance of the
// parameters marked in `estimate` (in Parameter order) that no unbiased
// estimator can beat, from the information of every fix and fix interval at
// the true poses (the base pose at each fix time inside the encoder
// recording, as many as CalibrationProblem keeps) and true parameters.
Eigen::MatrixXd CramerRaoCovariance(const std::vector<EncoderSample>& encoders,
                                    const std::vector<Fix>& fixes,
                                    const std::vector<geometry::Pose2D>& true_poses,
                                    const kinematics::RobotParameters& truth,
                                    const CalibrationOptions& options);

// Open-loop dead reckoning of the fix sensor over the fixes inside the encoder
// recording, started at the first of them: RMS position error against those
// fixes (how far odometry alone drifts); 0 when no fix is inside.
double DeadReckoningRms(const std::vector<EncoderSample>& encoders, const std::vector<Fix>& fixes,
                        const kinematics::RobotParameters& parameters);

// Which manoeuvres make which parameters observable, for users planning a recording.
std::string TrajectoryAdvice();

}  // namespace structloc::calibration_core
