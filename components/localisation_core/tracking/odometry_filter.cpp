// The pose + odometry-calibration filter (see header).
#include "structloc/localisation_core/tracking/odometry_filter.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace structloc::localisation_core {
namespace {

// Rotation of a robot-frame increment into the map frame (heading untouched).
Eigen::Matrix3d Rotation(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  r(0, 0) = c;
  r(0, 1) = -s;
  r(1, 0) = s;
  r(1, 1) = c;
  return r;
}

}  // namespace

OdometryFilter::OdometryFilter(const OdometryFilterOptions& options) : options_(options) {
  Reset(geometry::Pose2D{}, Eigen::Matrix3d::Identity());
  reset_ = false;  // the first real Reset still sets the factors' initial sigmas
}

void OdometryFilter::Reset(const geometry::Pose2D& pose, const Eigen::Matrix3d& covariance) {
  const Eigen::Matrix3d calibration = covariance_.bottomRightCorner<3, 3>();
  const bool first = !reset_;
  reset_ = true;
  pose_ = pose;
  covariance_.setZero();
  covariance_.topLeftCorner<3, 3>() = covariance;
  if (first) {
    // A factor that is not estimated keeps a tiny variance so the matrix stays invertible.
    const double s2 = std::max(options_.scale_sigma * options_.scale_sigma, 1e-12);
    const double d2 =
        std::max(options_.drift_sigma_rad_per_m * options_.drift_sigma_rad_per_m, 1e-12);
    covariance_.bottomRightCorner<3, 3>() = Eigen::Vector3d(s2, s2, d2).asDiagonal();
  } else {
    covariance_.bottomRightCorner<3, 3>() = calibration;
  }
}

Eigen::Vector3d OdometryFilter::CalibrationSigma() const {
  return covariance_.bottomRightCorner<3, 3>().diagonal().cwiseSqrt();
}

void OdometryFilter::Predict(const geometry::Pose2D& step) {
  const double d = std::hypot(step.x, step.y);
  const double scale = calibration_.x(), turn = calibration_.y(), drift = calibration_.z();
  const geometry::Pose2D m{scale * step.x, scale * step.y, turn * step.theta + drift * d};
  const double c = std::cos(pose_.theta), s = std::sin(pose_.theta);
  Matrix6d f = Matrix6d::Identity();
  // d(pose + R m)/d(pose): the heading turns the increment.
  f(0, 2) = -s * m.x - c * m.y;
  f(1, 2) = c * m.x - s * m.y;
  // d(R m)/d(factors).
  Eigen::Matrix3d dm = Eigen::Matrix3d::Zero();
  dm(0, 0) = step.x;
  dm(1, 0) = step.y;
  dm(2, 1) = step.theta;
  dm(2, 2) = d;
  const Eigen::Matrix3d rot = Rotation(pose_.theta);
  f.topRightCorner<3, 3>() = rot * dm;
  // Random error of the step, in the robot frame: a random walk, its variance
  // growing with the distance driven and the angle turned.
  const double vxy = options_.sigma_xy_per_m * options_.sigma_xy_per_m * d;
  const double vt =
      options_.sigma_theta_per_m * options_.sigma_theta_per_m * d +
      options_.sigma_theta_per_rad * options_.sigma_theta_per_rad * std::abs(step.theta);
  const Eigen::Matrix3d q =
      rot * Eigen::Vector3d(vxy + 1e-8, vxy + 1e-8, vt + 1e-10).asDiagonal() * rot.transpose();
  // Exactly symmetric despite rounding: the localiser refuses a prior that is
  // not (an asymmetry of 8e-8 once stalled the tracker on Freiburg 079).
  covariance_ = f * covariance_ * f.transpose();
  covariance_ = 0.5 * (covariance_ + covariance_.transpose());
  covariance_.topLeftCorner<3, 3>() += q;
  const double walk = options_.calibration_walk_per_m * options_.calibration_walk_per_m * d;
  if (options_.scale_sigma > 0.0) {
    covariance_(3, 3) += walk;
    covariance_(4, 4) += walk;
  }
  if (options_.drift_sigma_rad_per_m > 0.0) covariance_(5, 5) += walk;
  pose_ = geometry::Compose(pose_, m);
}

int OdometryFilter::Update(const Eigen::Matrix3d& information, const Eigen::Vector3d& gradient) {
  // Keep the eigen-directions the features pin well enough (the test of the
  // localiser's observability check); project the gradient onto them.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 *
                                                           (information + information.transpose()));
  Eigen::Matrix3d pinned = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d projector = Eigen::Matrix3d::Zero();
  int used = 0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d v = eig.eigenvectors().col(k);
    const double lambda = eig.eigenvalues()(k);
    const double limit =
        v.head<2>().norm() * options_.weak_std_m + std::abs(v.z()) * options_.weak_std_rad;
    if (!(lambda > 0.0) || 1.0 / std::sqrt(lambda) > limit) continue;
    pinned += lambda * v * v.transpose();
    projector += v * v.transpose();
    ++used;
  }
  if (used == 0) return 0;
  Matrix6d info = covariance_.ldlt().solve(Matrix6d::Identity());
  info.topLeftCorner<3, 3>() += pinned;
  Matrix6d updated = info.ldlt().solve(Matrix6d::Identity());
  updated = 0.5 * (updated + updated.transpose());
  Vector6d g = Vector6d::Zero();
  g.head<3>() = projector * gradient;
  const Vector6d delta = updated * g;
  if (!delta.allFinite() || !updated.allFinite()) return 0;
  pose_.x += delta(0);
  pose_.y += delta(1);
  pose_.theta = geometry::WrapAngle(pose_.theta + delta(2));
  calibration_ += delta.tail<3>();
  covariance_ = updated;
  return used;
}

}  // namespace structloc::localisation_core
