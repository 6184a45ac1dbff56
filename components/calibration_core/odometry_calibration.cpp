// Odometry calibration (see header).
#include "odometry_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "calibration_diagnosis.hpp"
#include "strict_xml.hpp"
#include "tricycle.hpp"

namespace structloc::calibration {

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

using Vector = Eigen::VectorXd;

// The encoder motion between two fixes: tick increments (unwrapped, possibly
// fractional at the ends) and the steering reading that applies to each.
struct Interval {
  std::vector<std::pair<double, double>> steps;  // (tick delta, steering ticks)
  geometry::Pose2D measured;                     // fix i -> fix j, in fix i's frame
  Eigen::Matrix3d information;                   // inverse covariance of `measured`
};

kinematics::RobotParameters Apply(const kinematics::RobotParameters& base,
                                  const std::array<double, kParameterCount>& v) {
  kinematics::RobotParameters p = base;
  p.wheel_radius = v[kWheelRadius];
  p.axle_distance = v[kAxleDistance];
  p.steering_offset = v[kSteeringOffset];
  p.steering_rad_per_tick = v[kSteeringGain];
  p.sensor = {v[kSensorX], v[kSensorY], v[kSensorTheta]};
  return p;
}

std::array<double, kParameterCount> Values(const kinematics::RobotParameters& p) {
  return {p.wheel_radius, p.axle_distance, p.steering_offset, p.steering_rad_per_tick,
          p.sensor.x,     p.sensor.y,      p.sensor.theta};
}

// Dead reckoning of the reference point over one interval, as a relative pose.
geometry::Pose2D Rerun(const std::vector<std::pair<double, double>>& steps,
                       const kinematics::RobotParameters& p) {
  geometry::Pose2D pose;
  const double rad_per_tick = 2.0 * geometry::kPi / p.traction_ticks_per_rev;
  for (const auto& [ticks, steering] : steps) {
    pose = kinematics::Advance(pose, ticks * rad_per_tick, p.SteeringAngle(steering),
                               p.wheel_radius, p.axle_distance);
  }
  return pose;
}

// Residual of one interval: measured minus predicted relative sensor motion.
Eigen::Vector3d Residual(const Interval& in, const kinematics::RobotParameters& p) {
  const geometry::Pose2D base = Rerun(in.steps, p);
  const geometry::Pose2D predicted =
      geometry::Compose(geometry::Inverse(p.sensor), geometry::Compose(base, p.sensor));
  return {in.measured.x - predicted.x, in.measured.y - predicted.y,
          geometry::WrapAngle(in.measured.theta - predicted.theta)};
}

class Problem {
 public:
  Problem(const std::vector<EncoderSample>& encoders, const std::vector<Fix>& fixes,
          const kinematics::RobotParameters& nominal, const CalibrationOptions& o,
          CalibrationReport& report)
      : nominal_(nominal), o_(o) {
    // Unwrapped cumulative traction ticks at every sample.
    std::vector<double> cumulative(encoders.size(), 0.0);
    for (size_t k = 1; k < encoders.size(); ++k) {
      cumulative[k] =
          cumulative[k - 1] + static_cast<double>(nominal.TickDelta(encoders[k - 1].traction_ticks,
                                                                    encoders[k].traction_ticks));
      if (encoders[k].t - encoders[k - 1].t > o.max_encoder_gap_s) ++report.encoder_gaps;
    }
    auto locate = [&](double t) -> std::optional<size_t> {  // index k with t_k <= t < t_{k+1}
      if (t < encoders.front().t || t >= encoders.back().t) return std::nullopt;
      const auto it = std::upper_bound(encoders.begin(), encoders.end(), t,
                                       [](double v, const EncoderSample& s) { return v < s.t; });
      return static_cast<size_t>(it - encoders.begin()) - 1;
    };
    auto ticks_at = [&](size_t k, double t) {
      const double f = (t - encoders[k].t) / (encoders[k + 1].t - encoders[k].t);
      return cumulative[k] + f * (cumulative[k + 1] - cumulative[k]);
    };
    // Pairs of fixes far enough apart to carry information.
    size_t i = 0;
    while (i + 1 < fixes.size()) {
      size_t j = i + 1;
      while (j < fixes.size()) {
        const geometry::Pose2D rel = geometry::Between(fixes[i].pose, fixes[j].pose);
        if (rel.Translation().norm() >= o.min_fix_travel_m ||
            std::abs(rel.theta) >= o.min_fix_turn_rad)
          break;
        ++j;
      }
      if (j >= fixes.size()) break;
      const auto ki = locate(fixes[i].t), kj = locate(fixes[j].t);
      bool ok = ki && kj;
      for (size_t k = ki.value_or(0); ok && k < kj.value_or(0) + 1; ++k) {
        ok = encoders[k + 1].t - encoders[k].t <= o.max_encoder_gap_s;
      }
      if (!ok) {
        ++report.intervals_skipped;
        i = j;
        continue;
      }
      Interval in;
      double previous = ticks_at(*ki, fixes[i].t);
      for (size_t k = *ki + 1; k <= *kj; ++k) {
        in.steps.emplace_back(cumulative[k] - previous, encoders[k].steering_ticks);
        previous = cumulative[k];
      }
      in.steps.emplace_back(ticks_at(*kj, fixes[j].t) - previous, encoders[*kj + 1].steering_ticks);
      in.measured = geometry::Between(fixes[i].pose, fixes[j].pose);
      // Covariance of the relative motion, in fix i's frame.
      Eigen::Vector3d vi = fixes[i].has_variance ? fixes[i].variance : Default();
      Eigen::Vector3d vj = fixes[j].has_variance ? fixes[j].variance : Default();
      const double c = std::cos(fixes[i].pose.theta), s = std::sin(fixes[i].pose.theta);
      Eigen::Matrix2d rot;
      rot << c, s, -s, c;
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      cov.topLeftCorner<2, 2>() =
          rot * Eigen::Vector2d(vi.x() + vj.x(), vi.y() + vj.y()).asDiagonal() * rot.transpose();
      cov(2, 2) = vi.z() + vj.z();
      cov.diagonal().array() += 1e-12;
      in.information = cov.inverse();
      intervals_.push_back(std::move(in));
      i = j;
    }
  }

  Eigen::Vector3d Default() const {
    return {o_.default_sigma_xy_m * o_.default_sigma_xy_m,
            o_.default_sigma_xy_m * o_.default_sigma_xy_m,
            o_.default_sigma_theta_rad * o_.default_sigma_theta_rad};
  }

  size_t Size() const { return intervals_.size(); }

  // Whitened residuals (3 per interval) for the full parameter set.
  Vector Whitened(const std::array<double, kParameterCount>& v) const {
    const auto p = Apply(nominal_, v);
    Vector r(static_cast<Eigen::Index>(3 * intervals_.size()));
    for (size_t k = 0; k < intervals_.size(); ++k) {
      const Eigen::Matrix3d l = Eigen::LLT<Eigen::Matrix3d>(intervals_[k].information).matrixU();
      r.segment<3>(static_cast<Eigen::Index>(3 * k)) = l * Residual(intervals_[k], p);
    }
    return r;
  }

 private:
  kinematics::RobotParameters nominal_;
  CalibrationOptions o_;
  std::vector<Interval> intervals_;
};

std::string Text(double value, int digits = 4) {
  std::ostringstream out;
  out << std::setprecision(digits) << value;
  return out.str();
}

double Rms(const Vector& r) {
  return r.size() ? std::sqrt(r.squaredNorm() / static_cast<double>(r.size())) : 0.0;
}

// Huber weight per interval from its whitened 3-vector.
Vector HuberWeights(const Vector& r, double k) {
  Vector w(r.size());
  for (Eigen::Index i = 0; i + 2 < r.size(); i += 3) {
    const double n = r.segment<3>(i).norm();
    w.segment<3>(i).setConstant(n <= k ? 1.0 : k / n);
  }
  return w;
}

CalibrationReport Fail(CalibrationReport report, const std::vector<EncoderSample>& encoders,
                       const std::vector<Fix>& fixes, const kinematics::RobotParameters& nominal,
                       const std::string& failure) {
  report.success = false;
  report.failure = failure;
  report.likely_causes = LikelyCauses(encoders, fixes, nominal);
  return report;
}

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
             " between t = " + Text(encoders[k - 1].t, 12) + " and " + Text(encoders[k].t, 12) +
             " s (" + Text(distance) + " m with the nominal parameters, faster than " +
             Text(options.max_wheel_speed_m_s) + " m/s)";
    }
  }
  return std::nullopt;
}

// Whether an estimate deserves the name: finite residuals, mostly inliers,
// plausible values, and open-loop dead reckoning better than with the nominal
// parameters (an independent check of the relative-motion fit).
CalibrationReport Judge(CalibrationReport report, const std::vector<EncoderSample>& encoders,
                        const std::vector<Fix>& fixes, const kinematics::RobotParameters& nominal,
                        const CalibrationOptions& options) {
  if (!std::isfinite(report.residual_rms_after)) {
    return Fail(std::move(report), encoders, fixes, nominal,
                "the residuals with the estimated parameters are not finite");
  }
  const double outlier_fraction = static_cast<double>(report.intervals_downweighted) /
                                  static_cast<double>(report.intervals_used);
  if (outlier_fraction > options.max_outlier_fraction) {
    return Fail(std::move(report), encoders, fixes, nominal,
                std::to_string(report.intervals_downweighted) + " of " +
                    std::to_string(report.intervals_used) +
                    " fix intervals are outliers (more than " +
                    Text(100 * options.max_outlier_fraction) +
                    " %): the odometry model does not explain the fixes");
  }
  try {
    report.parameters.Validate();
  } catch (const std::invalid_argument& e) {
    return Fail(std::move(report), encoders, fixes, nominal,
                std::string("the estimate is implausible: ") + e.what());
  }
  report.dead_reckoning_rms_nominal = DeadReckoningRms(encoders, fixes, nominal);
  report.dead_reckoning_rms_calibrated = DeadReckoningRms(encoders, fixes, report.parameters);
  // Equal is fine: re-calibrating a calibrated robot confirms its parameters.
  if (!(report.dead_reckoning_rms_calibrated <=
        options.max_dead_reckoning_ratio * report.dead_reckoning_rms_nominal)) {
    return Fail(std::move(report), encoders, fixes, nominal,
                "dead reckoning with the estimate is worse than with the nominal "
                "parameters (RMS against the fixes " +
                    Text(report.dead_reckoning_rms_calibrated) + " m calibrated, " +
                    Text(report.dead_reckoning_rms_nominal) + " m nominal)");
  }
  report.success = true;
  return report;
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
  if (const auto jump = ImplausibleEncoderStep(encoders, nominal, options)) {
    return Fail(std::move(report), encoders, fixes, nominal, *jump);
  }
  const Problem problem(encoders, fixes, nominal, options, report);
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
  std::array<double, kParameterCount> values = Values(nominal);
  report.residual_rms_before = Rms(problem.Whitened(values));
  if (!std::isfinite(report.residual_rms_before)) {
    return Fail(std::move(report), encoders, fixes, nominal,
                "the residuals with the nominal parameters are not finite");
  }
  std::array<bool, kParameterCount> active = options.estimate;
  const std::array<double, kParameterCount> step_scale{1e-4, 1e-3, 1e-4, 1e-7, 1e-3, 1e-3, 1e-4};

  for (int attempt = 0; attempt < kParameterCount; ++attempt) {
    std::vector<int> index;
    for (int k = 0; k < kParameterCount; ++k) {
      if (active[static_cast<size_t>(k)]) index.push_back(k);
    }
    const Eigen::Index n = static_cast<Eigen::Index>(index.size());
    if (n == 0) break;  // every requested parameter proved unobservable
    values = Values(nominal);
    Vector r = problem.Whitened(values);
    Vector w = HuberWeights(r, options.huber_k);
    double cost = (w.array() * r.array().square()).sum();
    double lambda = 1e-3;
    Eigen::MatrixXd jacobian(r.size(), n);
    auto jacobian_at = [&](const std::array<double, kParameterCount>& v) {
      for (Eigen::Index c = 0; c < n; ++c) {
        auto plus = v, minus = v;
        const double h = step_scale[static_cast<size_t>(index[static_cast<size_t>(c)])];
        plus[static_cast<size_t>(index[static_cast<size_t>(c)])] += h;
        minus[static_cast<size_t>(index[static_cast<size_t>(c)])] -= h;
        jacobian.col(c) = (problem.Whitened(plus) - problem.Whitened(minus)) / (2 * h);
      }
    };
    int it = 0;
    for (; it < options.max_iterations; ++it) {
      jacobian_at(values);
      const Eigen::MatrixXd h = jacobian.transpose() * w.asDiagonal() * jacobian;
      const Vector g = jacobian.transpose() * (w.array() * r.array()).matrix();
      bool improved = false;
      for (int tries = 0; tries < 10 && !improved; ++tries) {
        Eigen::MatrixXd damped = h;
        damped.diagonal() += lambda * h.diagonal().cwiseMax(1e-12);
        const Vector delta = -damped.ldlt().solve(g);
        auto candidate = values;
        for (Eigen::Index c = 0; c < n; ++c)
          candidate[static_cast<size_t>(index[static_cast<size_t>(c)])] += delta(c);
        if (candidate[kWheelRadius] <= 0 || candidate[kAxleDistance] <= 0 || !delta.allFinite()) {
          lambda *= 10;
          continue;
        }
        const Vector rc = problem.Whitened(candidate);
        const Vector wc = HuberWeights(rc, options.huber_k);
        const double cc = (wc.array() * rc.array().square()).sum();
        if (cc < cost) {
          const double gain = (cost - cc) / std::max(cost, 1e-300);
          values = candidate;
          r = rc;
          w = wc;
          cost = cc;
          lambda = std::max(lambda / 10, 1e-9);
          improved = gain >= 1e-12;  // converged when the cost stops falling
        } else {
          lambda *= 10;
        }
      }
      if (!improved) break;
    }
    report.iterations = std::min(it + 1, options.max_iterations);
    // Uncertainty: inverse of the weighted normal matrix, scaled by the residuals.
    std::array<double, kParameterCount> std{};
    int worst = -1;
    double worst_ratio = 1.0;
    jacobian_at(values);
    const Eigen::MatrixXd h = jacobian.transpose() * w.asDiagonal() * jacobian;
    const double dof = std::max(1.0, static_cast<double>(r.size() - n));
    const double scale = std::max(1.0, cost / dof);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(h);
    const double largest = eig.eigenvalues().maxCoeff();
    Eigen::VectorXd inv = eig.eigenvalues();
    for (Eigen::Index k = 0; k < inv.size(); ++k)
      inv(k) = inv(k) > 1e-12 * largest ? 1.0 / inv(k) : 1e300;
    const Eigen::MatrixXd covariance =
        scale * eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
    for (Eigen::Index c = 0; c < n; ++c) {
      const size_t k = static_cast<size_t>(index[static_cast<size_t>(c)]);
      std[k] = std::sqrt(std::max(0.0, covariance(c, c)));
      const double ratio = std[k] / options.max_std[k];
      if (!(ratio <= worst_ratio)) {
        worst_ratio = std::isfinite(ratio) ? ratio : 1e300;
        worst = static_cast<int>(k);
      }
    }
    if (worst >= 0) {
      const auto p = static_cast<Parameter>(worst);
      std::string why = "";
      if (p == kAxleDistance || p == kSteeringOffset || p == kSteeringGain) {
        why = " (the trajectory turns too little: drive curves both ways)";
      } else if (p == kSensorX || p == kSensorY || p == kSensorTheta) {
        why = " (turn on the spot or in tight curves to separate the sensor's mounting)";
      } else {
        why = " (drive longer straight runs)";
      }
      report.warnings.push_back(std::string(ParameterName(p)) +
                                " is not observable from this trajectory" + why +
                                ": kept at its nominal value");
      active[static_cast<size_t>(worst)] = false;
      continue;  // re-estimate without it
    }
    report.parameters = Apply(nominal, values);
    report.estimated = active;
    report.standard_deviation = std;
    report.correlation = Eigen::MatrixXd::Identity(n, n);
    for (Eigen::Index a = 0; a < n; ++a) {
      for (Eigen::Index b = 0; b < n; ++b) {
        report.correlation(a, b) =
            covariance(a, b) / std::sqrt(covariance(a, a) * covariance(b, b));
      }
    }
    report.residual_rms_after = Rms(r);
    for (Eigen::Index k = 0; k + 2 < r.size(); k += 3) {
      if (w(k) < 0.5) ++report.intervals_downweighted;
    }
    if (report.intervals_downweighted > 0) {
      report.warnings.push_back(std::to_string(report.intervals_downweighted) +
                                " fix intervals look like outliers and were down-weighted");
    }
    return Judge(std::move(report), encoders, fixes, nominal, options);
  }
  return Fail(std::move(report), encoders, fixes, nominal,
              "no parameter could be estimated from this trajectory");
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

}  // namespace structloc::calibration
