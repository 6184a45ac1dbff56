// Odometry with realistic errors from known poses (see header).
#include "structloc/simulation_core/odometry_errors.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace structloc::simulation_core {

void OdometryErrorModel::Validate() const {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  require(std::isfinite(scale_error) && scale_error > -1.0,
          "scale_error must be a finite number above -1");
  require(std::isfinite(heading_drift_rad_per_m), "heading_drift_rad_per_m must be finite");
  require(std::isfinite(noise_xy_m_per_sqrt_m) && noise_xy_m_per_sqrt_m >= 0.0,
          "noise_xy_m_per_sqrt_m must be finite and >= 0");
  require(std::isfinite(noise_theta_rad_per_sqrt_m) && noise_theta_rad_per_sqrt_m >= 0.0,
          "noise_theta_rad_per_sqrt_m must be finite and >= 0");
  require(std::isfinite(turn_scale_error) && turn_scale_error > -1.0,
          "turn_scale_error must be a finite number above -1");
  require(std::isfinite(noise_theta_rad_per_sqrt_rad) && noise_theta_rad_per_sqrt_rad >= 0.0,
          "noise_theta_rad_per_sqrt_rad must be finite and >= 0");
}

OdometrySynthesiser::OdometrySynthesiser(const OdometryErrorModel& model, std::mt19937& rng,
                                         const geometry::Pose2D& start)
    : model_(model), rng_(rng), previous_known_(start), odometry_(start) {
  model_.Validate();
}

geometry::Pose2D OdometrySynthesiser::Next(const geometry::Pose2D& known) {
  geometry::Pose2D step = geometry::Between(previous_known_, known);
  previous_known_ = known;
  const double distance = std::hypot(step.x, step.y);
  const double root = std::sqrt(distance);
  const double turn_root = std::sqrt(std::abs(step.theta));
  step.x = step.x * (1.0 + model_.scale_error) + model_.noise_xy_m_per_sqrt_m * root * unit_(rng_);
  step.y = step.y * (1.0 + model_.scale_error) + model_.noise_xy_m_per_sqrt_m * root * unit_(rng_);
  step.theta = step.theta * (1.0 + model_.turn_scale_error) +
               model_.heading_drift_rad_per_m * distance +
               model_.noise_theta_rad_per_sqrt_m * root * unit_(rng_);
  // Drawn only when asked for, so that logs synthesised without it keep
  // their noise sequence.
  if (model_.noise_theta_rad_per_sqrt_rad > 0.0)
    step.theta += model_.noise_theta_rad_per_sqrt_rad * turn_root * unit_(rng_);
  odometry_ = geometry::Compose(odometry_, step);
  odometry_.theta = geometry::WrapAngle(odometry_.theta);
  return odometry_;
}

double RestampedTime(double previous_stamp, const geometry::Pose2D& from,
                     const geometry::Pose2D& to, double speed_m_s, double turn_rate_rad_s,
                     double min_step_s) {
  const double distance = std::hypot(to.x - from.x, to.y - from.y);
  const double turn = std::abs(geometry::WrapAngle(to.theta - from.theta));
  return previous_stamp + std::max({min_step_s, distance / speed_m_s, turn / turn_rate_rad_s});
}

}  // namespace structloc::simulation_core
