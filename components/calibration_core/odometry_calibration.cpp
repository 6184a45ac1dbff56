// Odometry calibration (see header): checks the inputs, builds the problem,
// fits the observable parameters and judges the result.
#include "structloc/calibration_core/odometry_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "structloc/calibration_core/batch_solver.hpp"
#include "structloc/calibration_core/calibration_problem.hpp"
#include "structloc/calibration_core/calibration_report_builder.hpp"
#include "structloc/calibration_core/information_statement.hpp"
#include "structloc/calibration_core/observability_pruning.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/kinematics/tricycle.hpp"

namespace structloc::calibration_core {

const char* ParameterName(Parameter p) {
  static const char* names[] = {"wheel_radius",          "axle_distance",     "steering_offset",
                                "steering_rad_per_tick", "sensor_x",          "sensor_y",
                                "sensor_theta",          "left_wheel_radius", "right_wheel_radius",
                                "wheel_separation"};
  return names[p];
}

const char* ParameterUnit(Parameter p) {
  static const char* units[] = {"m", "m", "rad", "rad/tick", "m", "m", "rad", "m", "m", "m"};
  return units[p];
}

bool IsScale(Parameter p) {
  return p == kWheelRadius || p == kAxleDistance || p == kSteeringGain || p == kLeftWheelRadius ||
         p == kRightWheelRadius || p == kWheelSeparation;
}

bool AppliesTo(Parameter p, kinematics::DriveKind kind) {
  if (p == kSensorX || p == kSensorY || p == kSensorTheta) return true;
  const bool differential =
      p == kLeftWheelRadius || p == kRightWheelRadius || p == kWheelSeparation;
  return differential == (kind == kinematics::DriveKind::kDifferential);
}

std::array<bool, kParameterCount> DefaultEstimate(kinematics::DriveKind kind) {
  std::array<bool, kParameterCount> estimate{};
  if (kind == kinematics::DriveKind::kDifferential) {
    estimate[kLeftWheelRadius] = estimate[kRightWheelRadius] = estimate[kWheelSeparation] = true;
  } else {
    estimate[kWheelRadius] = estimate[kAxleDistance] = estimate[kSteeringOffset] = true;
  }
  return estimate;
}

std::array<bool, kParameterCount> ParseParameterList(const std::string& list) {
  std::string names;
  for (int k = 0; k < kParameterCount; ++k) {
    names += std::string(k > 0 ? ", " : "") + ParameterName(static_cast<Parameter>(k));
  }
  if (list.empty()) {
    throw config::ConfigError("--estimate is empty; name at least one of " + names);
  }
  std::array<bool, kParameterCount> chosen{};
  size_t start = 0;
  while (true) {
    const size_t comma = list.find(',', start);
    const std::string name = list.substr(start, comma == std::string::npos ? comma : comma - start);
    bool known = false;
    for (int k = 0; k < kParameterCount; ++k) {
      if (name == ParameterName(static_cast<Parameter>(k))) {
        chosen[static_cast<size_t>(k)] = known = true;
      }
    }
    if (!known) {
      throw config::ConfigError("--estimate '" + list + "': " +
                                (name.empty() ? std::string("empty parameter name")
                                              : "unknown parameter '" + name + "'") +
                                "; choose from " + names);
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return chosen;
}

void CalibrationOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("calibration: ") + what);
  };
  require(default_sigma_xy_m > 0 && default_sigma_theta_rad > 0, "default sigmas must be > 0");
  require(min_fix_travel_m >= 0 && min_fix_turn_rad >= 0, "fix spacing must be >= 0");
  require(slip_variance_m2_per_m >= 0 && std::isfinite(slip_variance_m2_per_m),
          "slip_variance_m2_per_m must be finite and >= 0");
  require(heading_variance_rad2_per_m >= 0 && std::isfinite(heading_variance_rad2_per_m),
          "heading_variance_rad2_per_m must be finite and >= 0");
  require(huber_k > 0, "huber_k must be > 0");
  require(max_iterations >= 1, "max_iterations must be >= 1");
  require(max_encoder_gap_s > 0, "max_encoder_gap_s must be > 0");
  require(std::find(estimate.begin(), estimate.end(), true) != estimate.end(),
          "no parameter to estimate");
  require(max_outlier_fraction >= 0 && max_outlier_fraction <= 1,
          "max_outlier_fraction must be within 0..1");
  require(max_dead_reckoning_ratio > 0, "max_dead_reckoning_ratio must be > 0");
  require(dead_reckoning_tolerance >= 0, "dead_reckoning_tolerance must be >= 0");
  require(max_wheel_speed_m_s > 0, "max_wheel_speed_m_s must be > 0");
}

namespace {

// The counters of one sample that drive the robot: the traction wheel's,
// or the left and the right wheel's.
std::vector<std::pair<const char*, uint64_t>> Counters(const EncoderSample& s,
                                                       const kinematics::RobotParameters& p) {
  if (p.kind == kinematics::DriveKind::kDifferential) {
    return {{"left wheel", s.left_ticks}, {"right wheel", s.right_ticks}};
  }
  return {{"traction", s.traction_ticks}};
}

double RadiusOf(const char* counter, const kinematics::RobotParameters& p) {
  if (p.kind == kinematics::DriveKind::kTricycle) return p.wheel_radius;
  return std::string(counter) == "left wheel" ? p.left_wheel_radius : p.right_wheel_radius;
}

// The first encoder step that moves a wheel faster than the options allow
// with the nominal parameters, described; nullopt when there is none.
std::optional<std::string> ImplausibleEncoderStep(const std::vector<EncoderSample>& encoders,
                                                  const kinematics::RobotParameters& nominal,
                                                  const CalibrationOptions& options) {
  for (size_t k = 1; k < encoders.size(); ++k) {
    const auto before = Counters(encoders[k - 1], nominal);
    const auto after = Counters(encoders[k], nominal);
    for (size_t c = 0; c < after.size(); ++c) {
      const int64_t delta = nominal.TickDelta(before[c].second, after[c].second);
      const double distance =
          std::abs(nominal.WheelAngle(delta) * RadiusOf(after[c].first, nominal));
      const double dt = encoders[k].t - encoders[k - 1].t;
      if (distance > options.max_wheel_speed_m_s * std::max(dt, 0.05)) {
        return std::string("the ") + after[c].first + " ticks jump by " + std::to_string(delta) +
               " between t = " + ShortNumber(encoders[k - 1].t, 12) + " and " +
               ShortNumber(encoders[k].t, 12) + " s (" + ShortNumber(distance) +
               " m with the nominal parameters, faster than " +
               ShortNumber(options.max_wheel_speed_m_s) + " m/s)";
      }
    }
  }
  return std::nullopt;
}

// Throws std::invalid_argument for encoder samples no calibration can use.
void CheckEncoders(const std::vector<EncoderSample>& encoders,
                   const kinematics::RobotParameters& nominal) {
  if (encoders.size() < 2)
    throw std::invalid_argument("calibration: fewer than two encoder samples");
  for (size_t k = 0; k < encoders.size(); ++k) {
    if (k > 0 && !(encoders[k].t > encoders[k - 1].t))
      throw std::invalid_argument("calibration: encoder times must increase");
    for (const auto& [name, ticks] : Counters(encoders[k], nominal)) {
      if (ticks > nominal.MaxTractionTick()) {
        throw std::invalid_argument("calibration: encoder sample " + std::to_string(k + 1) +
                                    " has " + name + " ticks " + std::to_string(ticks) +
                                    ", more than the robot's " +
                                    std::to_string(nominal.traction_counter_bits) +
                                    "-bit counter holds; check the robot file's counter bits");
      }
    }
  }
}

// Throws std::invalid_argument when a requested parameter is not one of the robot's kind.
void CheckEstimateFitsTheRobot(const CalibrationOptions& options,
                               const kinematics::RobotParameters& nominal) {
  for (int k = 0; k < kParameterCount; ++k) {
    const auto p = static_cast<Parameter>(k);
    if (options.estimate[static_cast<size_t>(k)] && !AppliesTo(p, nominal.kind)) {
      throw std::invalid_argument(
          std::string("calibration: ") + ParameterName(p) + " is not a parameter of a " +
          (nominal.kind == kinematics::DriveKind::kDifferential ? "differential-drive"
                                                                : "tricycle") +
          " robot");
    }
  }
}

// The indices of the parameters marked in `mask`.
std::vector<size_t> Indices(const ParameterMask& mask) {
  std::vector<size_t> index;
  for (size_t k = 0; k < mask.size(); ++k) {
    if (mask[k]) index.push_back(k);
  }
  return index;
}

// The solver from `start` (with the poses held at it when `hold_poses`).
BatchSolution Solve(const CalibrationProblem& problem, const CalibrationState& start,
                    const std::vector<size_t>& active, const CalibrationOptions& options,
                    bool hold_poses = false) {
  BatchSolverOptions solver;
  solver.max_iterations = options.max_iterations;
  solver.huber_k = options.huber_k;
  solver.hold_poses = hold_poses;
  return SolveBatch(problem, start, active, solver, [](const ParameterValues& v) {
    return v[kWheelRadius] > 0 && v[kAxleDistance] > 0 && v[kLeftWheelRadius] > 0 &&
           v[kRightWheelRadius] > 0 && v[kWheelSeparation] > 0;
  });
}

// The two problems of one calibration: the coarse relative-motion one that
// finds the parameters' neighbourhood from a nominal far from the truth, and
// the full one over every fix that refines them efficiently.
struct Problems {
  const CalibrationProblem& coarse;
  const CalibrationProblem& full;
};

// Robust estimate of the parameters marked in `active` together with the
// poses, starting from the fixes and (keeping the others at) the nominal values.
ParameterFit FitActiveParameters(const Problems& problems, const CalibrationOptions& options,
                                 const ParameterMask& active) {
  const std::vector<size_t> index = Indices(active);
  const BatchSolution coarse =
      Solve(problems.coarse, problems.coarse.Initial(), index, options, true);
  CalibrationState start = problems.full.Initial();
  start.values = coarse.state.values;
  ParameterFit fit;
  fit.solution = Solve(problems.full, start, index, options);
  fit.values = fit.solution.state.values;
  fit.covariance = CovarianceFromInformation(fit.solution.information, fit.solution.cost,
                                             fit.solution.degrees_of_freedom);
  for (size_t c = 0; c < index.size(); ++c) {
    const auto e = static_cast<Eigen::Index>(c);
    fit.standard_deviation[index[c]] = std::sqrt(std::max(0.0, fit.covariance(e, e)));
  }
  return fit;
}

}  // namespace

CalibrationReport Calibrate(const std::vector<EncoderSample>& encoders,
                            const std::vector<Fix>& fixes,
                            const kinematics::RobotParameters& nominal,
                            const CalibrationOptions& options) {
  options.Validate();
  nominal.Validate();
  CalibrationReport report;
  report.parameters = nominal;
  CheckEncoders(encoders, nominal);
  CheckEstimateFitsTheRobot(options, nominal);
  if (const auto jump = ImplausibleEncoderStep(encoders, nominal, options)) {
    return Fail(std::move(report), encoders, fixes, nominal, *jump);
  }
  const CalibrationProblem problem(encoders, fixes, nominal, options);
  report.encoder_gaps = problem.EncoderGaps();
  report.intervals_skipped = problem.IntervalsSkipped();
  if (problem.Size() < 5) {
    throw std::invalid_argument(
        "calibration: only " + std::to_string(problem.Size()) +
        " usable fix intervals inside the encoder recording (need 5 or more); "
        "check that fixes and encoders share one clock");
  }
  report.fixes_used = problem.FixCount();
  report.intervals_used = problem.Size();
  if (report.encoder_gaps > 0) {
    report.warnings.push_back(std::to_string(report.encoder_gaps) +
                              " gaps in the encoder stream; the fixes on either side are not "
                              "linked across them");
  }
  // The residuals reported before and after: the relative motion between
  // fixes (poses at the fixes), a figure that needs no solve.
  const CalibrationProblem coarse(encoders, fixes, nominal, options, ProblemScope::kRelativeMotion);
  const auto relative_rms = [&](const ParameterValues& values) {
    return Rms(coarse.Whitened(coarse.AtFixes(values)));
  };
  report.residual_rms_before = relative_rms(ValuesOf(nominal));
  if (!std::isfinite(report.residual_rms_before)) {
    return Fail(std::move(report), encoders, fixes, nominal,
                "the residuals with the nominal parameters are not finite");
  }
  const PrunedFit pruned =
      FitObservableParameters(options.estimate, options.max_std, [&](const ParameterMask& active) {
        return FitActiveParameters({coarse, problem}, options, active);
      });
  AddFit(report, pruned, nominal);
  if (!pruned.AnyEstimated()) {
    return Fail(std::move(report), encoders, fixes, nominal,
                "no parameter could be estimated from this trajectory");
  }
  report.residual_rms_after = relative_rms(pruned.fit.values);
  // Stated for every requested parameter, the pruned ones included.
  const std::vector<size_t> requested = Indices(options.estimate);
  // With the residuals' scale, as the reported deviations (CovarianceFromInformation).
  const BatchSolution& solution = pruned.fit.solution;
  const double scale = std::max(1.0, solution.cost / std::max(1.0, solution.degrees_of_freedom));
  report.observability = DescribeInformation(
      InformationAt(problem, solution.state, solution.weights, requested) / scale, requested,
      pruned.fit.values, options.max_std);
  return Judge(std::move(report), encoders, fixes, nominal, options);
}

Eigen::MatrixXd CramerRaoCovariance(const std::vector<EncoderSample>& encoders,
                                    const std::vector<Fix>& fixes,
                                    const std::vector<geometry::Pose2D>& true_poses,
                                    const kinematics::RobotParameters& truth,
                                    const CalibrationOptions& options) {
  options.Validate();
  const CalibrationProblem problem(encoders, fixes, truth, options);
  if (true_poses.size() != problem.FixCount()) {
    throw std::invalid_argument("CramerRaoCovariance: " + std::to_string(true_poses.size()) +
                                " true poses for " + std::to_string(problem.FixCount()) +
                                " fixes inside the encoder recording");
  }
  CalibrationState state;
  state.poses = true_poses;
  state.values = ValuesOf(truth);
  const std::vector<size_t> active = Indices(options.estimate);
  const Eigen::VectorXd unweighted = Eigen::VectorXd::Ones(problem.Whitened(state).size());
  return InformationAt(problem, state, unweighted, active).inverse();
}

double DeadReckoningRms(const std::vector<EncoderSample>& encoders, const std::vector<Fix>& fixes,
                        const kinematics::RobotParameters& p) {
  if (encoders.empty()) return 0.0;
  // Only fixes the encoders cover: odometry says nothing about the others.
  const auto inside = [&](const Fix& f) {
    return f.t >= encoders.front().t && f.t <= encoders.back().t;
  };
  const auto first = std::find_if(fixes.begin(), fixes.end(), inside);
  if (first == fixes.end()) return 0.0;
  // The base pose at the first fix, from the sensor pose and the mounting.
  const geometry::Pose2D start = geometry::Compose(first->pose, geometry::Inverse(p.sensor));
  kinematics::DeadReckoning dr(p, start);
  const auto add = [&](const EncoderSample& s) {
    if (p.kind == kinematics::DriveKind::kDifferential) {
      dr.AddWheels(s.left_ticks, s.right_ticks);
    } else {
      dr.Add(s.traction_ticks, s.steering_ticks);
    }
  };
  size_t k = 0;
  while (k < encoders.size() && encoders[k].t <= first->t) ++k;
  if (k > 0) --k;
  add(encoders[k]);
  double sum = 0.0;
  size_t n = 0;
  for (auto f = first; f != fixes.end() && inside(*f); ++f) {
    while (k + 1 < encoders.size() && encoders[k + 1].t <= f->t) {
      ++k;
      add(encoders[k]);
    }
    const geometry::Pose2D sensor = geometry::Compose(dr.Pose(), p.sensor);
    sum += (sensor.Translation() - f->pose.Translation()).squaredNorm();
    ++n;
  }
  return std::sqrt(sum / static_cast<double>(n));
}

std::string TrajectoryAdvice() {
  return "Which manoeuvres make which parameter observable:\n"
         "  wheel radius (distance per tick): straight runs of several metres;\n"
         "  axle distance: curves, in both directions, at different steering angles;\n"
         "  steering offset: curves both ways (left and right) and straight runs -\n"
         "    turning one way only mixes the offset up with the axle distance;\n"
         "  steering gain: curves at small and at large steering angles;\n"
         "  sensor mounting (x, y, theta): turns on the spot or tight curves, where\n"
         "    the sensor sweeps around the reference point.\n"
         "Differential drive:\n"
         "  left and right wheel radius: straight runs fix their mean, turns both\n"
         "    ways their difference (a robot that only curves one way mixes it up\n"
         "    with the wheel separation);\n"
         "  wheel separation: turns in both directions, on the spot or in curves.\n"
         "A figure of eight followed by a straight run there and back makes all of\n"
         "them observable; a straight line alone says nothing about the axle distance\n"
         "or the wheel separation.\n";
}

}  // namespace structloc::calibration_core
