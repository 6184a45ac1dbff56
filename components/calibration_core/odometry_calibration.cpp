// Odometry calibration (see header): checks the inputs, builds the problem,
// fits the observable parameters and judges the result.
#include "structloc/calibration_core/odometry_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "structloc/calibration_core/calibration_problem.hpp"
#include "structloc/calibration_core/calibration_report_builder.hpp"
#include "structloc/calibration_core/levenberg_marquardt.hpp"
#include "structloc/calibration_core/observability_pruning.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/kinematics/tricycle.hpp"

namespace structloc::calibration_core {

const char* ParameterName(Parameter p) {
  static const char* names[] = {"wheel_radius",          "axle_distance", "steering_offset",
                                "steering_rad_per_tick", "sensor_x",      "sensor_y",
                                "sensor_theta"};
  return names[p];
}

const char* ParameterUnit(Parameter p) {
  static const char* units[] = {"m", "m", "rad", "rad/tick", "m", "m", "rad"};
  return units[p];
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
  require(huber_k > 0, "huber_k must be > 0");
  require(max_iterations >= 1, "max_iterations must be >= 1");
  require(max_encoder_gap_s > 0, "max_encoder_gap_s must be > 0");
  require(std::find(estimate.begin(), estimate.end(), true) != estimate.end(),
          "no parameter to estimate");
  require(max_outlier_fraction >= 0 && max_outlier_fraction <= 1,
          "max_outlier_fraction must be within 0..1");
  require(max_dead_reckoning_ratio > 0, "max_dead_reckoning_ratio must be > 0");
  require(max_wheel_speed_m_s > 0, "max_wheel_speed_m_s must be > 0");
}

namespace {

// The first encoder step that moves the wheel faster than the options allow
// with the nominal parameters, described; nullopt when there is none.
std::optional<std::string> ImplausibleEncoderStep(const std::vector<EncoderSample>& encoders,
                                                  const kinematics::RobotParameters& nominal,
                                                  const CalibrationOptions& options) {
  for (size_t k = 1; k < encoders.size(); ++k) {
    const int64_t delta =
        nominal.TickDelta(encoders[k - 1].traction_ticks, encoders[k].traction_ticks);
    const double distance = std::abs(nominal.WheelAngle(delta) * nominal.wheel_radius);
    const double dt = encoders[k].t - encoders[k - 1].t;
    if (distance > options.max_wheel_speed_m_s * std::max(dt, 0.05)) {
      return "the traction ticks jump by " + std::to_string(delta) +
             " between t = " + ShortNumber(encoders[k - 1].t, 12) + " and " +
             ShortNumber(encoders[k].t, 12) + " s (" + ShortNumber(distance) +
             " m with the nominal parameters, faster than " +
             ShortNumber(options.max_wheel_speed_m_s) + " m/s)";
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
    if (encoders[k].traction_ticks > nominal.MaxTractionTick()) {
      throw std::invalid_argument(
          "calibration: encoder sample " + std::to_string(k + 1) + " has traction ticks " +
          std::to_string(encoders[k].traction_ticks) + ", more than the robot's " +
          std::to_string(nominal.traction_counter_bits) +
          "-bit counter holds; check traction_counter_bits");
    }
  }
}

// Robust Levenberg-Marquardt estimate of the parameters marked in `active`,
// starting from (and keeping the others at) the nominal values.
ParameterFit FitActiveParameters(const CalibrationProblem& problem,
                                 const kinematics::RobotParameters& nominal,
                                 const CalibrationOptions& options, const ParameterMask& active) {
  // Central-difference steps, in each parameter's unit.
  const ParameterValues step_scale{1e-4, 1e-3, 1e-4, 1e-7, 1e-3, 1e-3, 1e-4};
  const ParameterValues start = ValuesOf(nominal);
  std::vector<size_t> index;
  for (size_t k = 0; k < active.size(); ++k) {
    if (active[k]) index.push_back(k);
  }
  const Eigen::Index n = static_cast<Eigen::Index>(index.size());
  Eigen::VectorXd x0(n), steps(n);
  for (Eigen::Index c = 0; c < n; ++c) {
    x0(c) = start[index[static_cast<size_t>(c)]];
    steps(c) = step_scale[index[static_cast<size_t>(c)]];
  }
  const auto all_values = [&](const Eigen::VectorXd& x) {
    ParameterValues v = start;
    for (Eigen::Index c = 0; c < n; ++c) v[index[static_cast<size_t>(c)]] = x(c);
    return v;
  };
  const ResidualFunction residual = [&](const Eigen::VectorXd& x) {
    return problem.Whitened(all_values(x));
  };
  const JacobianFunction jacobian = [&](const Eigen::VectorXd& x) {
    return CentralDifferenceJacobian(residual, x, steps);
  };
  const FeasibleFunction feasible = [&](const Eigen::VectorXd& x) {
    const ParameterValues v = all_values(x);
    return !(v[kWheelRadius] <= 0 || v[kAxleDistance] <= 0);
  };
  LevenbergMarquardtOptions solver;
  solver.max_iterations = options.max_iterations;
  solver.huber_k = options.huber_k;
  solver.block_size = 3;  // x, y, theta of one fix interval
  ParameterFit fit;
  fit.solution = MinimiseRobustly(residual, jacobian, x0, solver, feasible);
  fit.values = all_values(fit.solution.x);
  fit.covariance =
      RobustCovariance(jacobian(fit.solution.x), fit.solution.weights, fit.solution.cost);
  for (Eigen::Index c = 0; c < n; ++c) {
    fit.standard_deviation[index[static_cast<size_t>(c)]] =
        std::sqrt(std::max(0.0, fit.covariance(c, c)));
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
  report.intervals_used = problem.Size();
  if (report.encoder_gaps > 0) {
    report.warnings.push_back(std::to_string(report.encoder_gaps) +
                              " gaps in the encoder stream; intervals across them were skipped");
  }
  report.residual_rms_before = Rms(problem.Whitened(ValuesOf(nominal)));
  if (!std::isfinite(report.residual_rms_before)) {
    return Fail(std::move(report), encoders, fixes, nominal,
                "the residuals with the nominal parameters are not finite");
  }
  const PrunedFit pruned =
      FitObservableParameters(options.estimate, options.max_std, [&](const ParameterMask& active) {
        return FitActiveParameters(problem, nominal, options, active);
      });
  AddFit(report, pruned, nominal);
  if (!pruned.AnyEstimated()) {
    return Fail(std::move(report), encoders, fixes, nominal,
                "no parameter could be estimated from this trajectory");
  }
  return Judge(std::move(report), encoders, fixes, nominal, options);
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
  size_t k = 0;
  while (k < encoders.size() && encoders[k].t <= first->t) ++k;
  if (k > 0) --k;
  dr.Add(encoders[k].traction_ticks, encoders[k].steering_ticks);
  double sum = 0.0;
  size_t n = 0;
  for (auto f = first; f != fixes.end() && inside(*f); ++f) {
    while (k + 1 < encoders.size() && encoders[k + 1].t <= f->t) {
      ++k;
      dr.Add(encoders[k].traction_ticks, encoders[k].steering_ticks);
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
         "    the sensor sweeps around the rear-axle middle.\n"
         "A figure of eight followed by a straight run there and back makes all of\n"
         "them observable; a straight line alone says nothing about the axle distance.\n";
}

}  // namespace structloc::calibration_core
