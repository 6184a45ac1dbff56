// The pose tracker's filter (beyond the thesis, whose prior is the odometry
// alone, 3.6): one extended Kalman filter over the robot pose in the map and
// three odometry calibration factors, the distance scale, the turn scale and
// the heading drift per metre driven. Odometry steps predict, corrected by the
// factors; each scan's feature information updates only the directions the
// features pin (a corridor's along-track direction, a doorway jamb's weak
// pull, stay with odometry), and through the cross terms the factors learn
// the odometry's systematic errors while the robot drives. DDS-free.
#pragma once

#include <Eigen/Core>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::localisation_core {

struct OdometryFilterOptions {
  double sigma_xy_per_m = 0.02;         // random odometry error per metre driven (1 sigma)
  double sigma_theta_per_m = 0.01;      // rad per metre driven
  double sigma_theta_per_rad = 0.02;    // rad per radian turned
  double scale_sigma = 0.0;             // initial sigma of the scale factors (0: not estimated)
  double drift_sigma_rad_per_m = 0.0;   // initial sigma of the heading drift per metre
  double calibration_walk_per_m = 0.0;  // growth of the factors' sigma per sqrt(metre)
  double weak_std_m = 0.05;             // directions the features pin worse than this ...
  double weak_std_rad = 0.05;           // ... (or this) are left to odometry
};

class OdometryFilter {
 public:
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  using Matrix6d = Eigen::Matrix<double, 6, 6>;

  explicit OdometryFilter(const OdometryFilterOptions& options);

  // A new pose and its covariance. The calibration factors learnt so far stay
  // (a relocalised robot keeps its wheels); their correlation with the old pose goes.
  void Reset(const geometry::Pose2D& pose, const Eigen::Matrix3d& covariance);
  // One odometry step (robot frame, from the previous to the current odometry pose).
  void Predict(const geometry::Pose2D& step);
  // Feature information about the pose and its gradient g = I (z - pose), from
  // the localiser's solve about the predicted pose. Returns the number of
  // directions used (0: nothing was pinned well enough, nothing changed).
  int Update(const Eigen::Matrix3d& information, const Eigen::Vector3d& gradient);

  geometry::Pose2D Pose() const { return pose_; }
  Eigen::Matrix3d PoseCovariance() const { return covariance_.topLeftCorner<3, 3>(); }
  // Distance scale, turn scale, heading drift (rad per metre): the factors the
  // odometry's steps are corrected with.
  Eigen::Vector3d Calibration() const { return calibration_; }
  Eigen::Vector3d CalibrationSigma() const;

 private:
  OdometryFilterOptions options_;
  geometry::Pose2D pose_;
  Eigen::Vector3d calibration_{1.0, 1.0, 0.0};
  Matrix6d covariance_ = Matrix6d::Identity();
  bool reset_ = false;  // the factors' sigmas have been set
};

}  // namespace structloc::localisation_core
