// The calibration's least-squares problem (see header).
#include "structloc/calibration_core/calibration_problem.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>

#include "structloc/kinematics/tricycle.hpp"

namespace structloc::calibration_core {

kinematics::RobotParameters WithValues(const kinematics::RobotParameters& base,
                                       const ParameterValues& values) {
  kinematics::RobotParameters p = base;
  p.wheel_radius = values[kWheelRadius];
  p.axle_distance = values[kAxleDistance];
  p.steering_offset = values[kSteeringOffset];
  p.steering_rad_per_tick = values[kSteeringGain];
  p.sensor = {values[kSensorX], values[kSensorY], values[kSensorTheta]};
  return p;
}

ParameterValues ValuesOf(const kinematics::RobotParameters& p) {
  return {p.wheel_radius, p.axle_distance, p.steering_offset, p.steering_rad_per_tick,
          p.sensor.x,     p.sensor.y,      p.sensor.theta};
}

namespace {

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

}  // namespace

CalibrationProblem::CalibrationProblem(const std::vector<EncoderSample>& encoders,
                                       const std::vector<Fix>& fixes,
                                       const kinematics::RobotParameters& nominal,
                                       const CalibrationOptions& options)
    : nominal_(nominal), options_(options) {
  // Unwrapped cumulative traction ticks at every sample.
  std::vector<double> cumulative(encoders.size(), 0.0);
  for (size_t k = 1; k < encoders.size(); ++k) {
    cumulative[k] =
        cumulative[k - 1] + static_cast<double>(nominal.TickDelta(encoders[k - 1].traction_ticks,
                                                                  encoders[k].traction_ticks));
    if (encoders[k].t - encoders[k - 1].t > options.max_encoder_gap_s) ++encoder_gaps_;
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
      if (rel.Translation().norm() >= options.min_fix_travel_m ||
          std::abs(rel.theta) >= options.min_fix_turn_rad)
        break;
      ++j;
    }
    if (j >= fixes.size()) break;
    const auto ki = locate(fixes[i].t), kj = locate(fixes[j].t);
    bool ok = ki && kj;
    for (size_t k = ki.value_or(0); ok && k < kj.value_or(0) + 1; ++k) {
      ok = encoders[k + 1].t - encoders[k].t <= options.max_encoder_gap_s;
    }
    if (!ok) {
      ++intervals_skipped_;
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
    in.information = RelativeInformation(fixes[i], fixes[j]);
    intervals_.push_back(std::move(in));
    i = j;
  }
}

Eigen::Vector3d CalibrationProblem::DefaultVariance() const {
  return {options_.default_sigma_xy_m * options_.default_sigma_xy_m,
          options_.default_sigma_xy_m * options_.default_sigma_xy_m,
          options_.default_sigma_theta_rad * options_.default_sigma_theta_rad};
}

// Inverse covariance of the relative motion from `from` to `to`, in `from`'s frame.
Eigen::Matrix3d CalibrationProblem::RelativeInformation(const Fix& from, const Fix& to) const {
  const Eigen::Vector3d vi = from.has_variance ? from.variance : DefaultVariance();
  const Eigen::Vector3d vj = to.has_variance ? to.variance : DefaultVariance();
  const double c = std::cos(from.pose.theta), s = std::sin(from.pose.theta);
  Eigen::Matrix2d rot;
  rot << c, s, -s, c;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov.topLeftCorner<2, 2>() =
      rot * Eigen::Vector2d(vi.x() + vj.x(), vi.y() + vj.y()).asDiagonal() * rot.transpose();
  cov(2, 2) = vi.z() + vj.z();
  cov.diagonal().array() += 1e-12;
  return cov.inverse();
}

Eigen::VectorXd CalibrationProblem::Whitened(const ParameterValues& values) const {
  const auto p = WithValues(nominal_, values);
  Eigen::VectorXd r(static_cast<Eigen::Index>(3 * intervals_.size()));
  for (size_t k = 0; k < intervals_.size(); ++k) {
    const Interval& in = intervals_[k];
    const Eigen::Matrix3d l = Eigen::LLT<Eigen::Matrix3d>(in.information).matrixU();
    // Measured minus predicted relative sensor motion.
    const geometry::Pose2D base = Rerun(in.steps, p);
    const geometry::Pose2D predicted =
        geometry::Compose(geometry::Inverse(p.sensor), geometry::Compose(base, p.sensor));
    const Eigen::Vector3d residual{in.measured.x - predicted.x, in.measured.y - predicted.y,
                                   geometry::WrapAngle(in.measured.theta - predicted.theta)};
    r.segment<3>(static_cast<Eigen::Index>(3 * k)) = l * residual;
  }
  return r;
}

}  // namespace structloc::calibration_core
