// The tracker's filter (odometry_filter.hpp): it learns the odometry's
// systematic errors from corrections, and leaves the directions a scan does
// not pin to odometry.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "structloc/localisation_core/tracking/odometry_filter.hpp"

namespace structloc::localisation_core {
namespace {

OdometryFilterOptions Learning() {
  OdometryFilterOptions o;
  o.sigma_xy_per_m = 0.005;
  o.sigma_theta_per_m = 0.002;
  o.scale_sigma = 0.03;
  o.drift_sigma_rad_per_m = 0.01;
  o.calibration_walk_per_m = 0.0001;
  return o;
}

// Full-pose information with sigma 1 cm and 0.3 deg, and its gradient for a
// measurement `z` seen from the filter's current pose.
void Observe(OdometryFilter& filter, const geometry::Pose2D& z) {
  const Eigen::Matrix3d information = Eigen::Vector3d(1e4, 1e4, 1.0 / (0.005 * 0.005)).asDiagonal();
  const geometry::Pose2D p = filter.Pose();
  const Eigen::Vector3d error(z.x - p.x, z.y - p.y, geometry::WrapAngle(z.theta - p.theta));
  EXPECT_EQ(filter.Update(information, information * error), 3);
}

TEST(OdometryFilter, LearnsTheScaleAndHeadingDriftOfTheOdometry) {
  OdometryFilter filter(Learning());
  geometry::Pose2D truth{0, 0, 0};
  filter.Reset(truth, Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
  const double scale_error = 0.02, drift_rad_per_m = 0.005;  // what the odometry gets wrong
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.005);
  // Laps of a 6 m x 4 m rectangle in 0.1 m steps, turning at the corners.
  for (int lap = 0; lap < 4; ++lap) {
    for (int side = 0; side < 4; ++side) {
      const int steps = side % 2 == 0 ? 60 : 40;
      for (int k = 0; k < steps; ++k) {
        const geometry::Pose2D true_step{0.1, 0.0, 0.0};
        truth = geometry::Compose(truth, true_step);
        const geometry::Pose2D odometry_step{0.1 * (1 + scale_error), 0.0, drift_rad_per_m * 0.1};
        filter.Predict(odometry_step);
        Observe(filter, {truth.x + noise(rng), truth.y + noise(rng), truth.theta});
      }
      const geometry::Pose2D turn{0.0, 0.0, geometry::kPi / 2};
      truth = geometry::Compose(truth, turn);
      filter.Predict(turn);
      Observe(filter, truth);
    }
  }
  const Eigen::Vector3d c = filter.Calibration();
  EXPECT_NEAR(c.x(), 1.0 / (1 + scale_error), 0.004);
  EXPECT_NEAR(c.y(), 1.0, 0.01);
  EXPECT_NEAR(c.z(), -drift_rad_per_m, 0.001);
  EXPECT_LT(filter.CalibrationSigma().x(), 0.01);
}

TEST(OdometryFilter, DirectionsTheScanDoesNotPinStayWithOdometry) {
  OdometryFilter filter(OdometryFilterOptions{});
  filter.Reset({1, 2, 0.3}, Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  // A corridor along x: only y is measured (0.5 cm), 10 cm off the prior;
  // the along-track information (x, sigma 20 cm) is too weak to be used.
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  information(1, 1) = 1.0 / (0.005 * 0.005);
  information(0, 0) = 1.0 / (0.2 * 0.2);
  const Eigen::Vector3d error(0.3, 0.1, 0.0);
  EXPECT_EQ(filter.Update(information, information * error), 1);
  EXPECT_DOUBLE_EQ(filter.Pose().x, 1.0);
  EXPECT_NEAR(filter.Pose().y, 2.1, 0.002);
  EXPECT_DOUBLE_EQ(filter.Pose().theta, 0.3);
  EXPECT_NEAR(filter.PoseCovariance()(0, 0), 0.01, 1e-12);
  EXPECT_LT(filter.PoseCovariance()(1, 1), 3e-5);
}

TEST(OdometryFilter, NothingPinnedChangesNothing) {
  OdometryFilter filter(OdometryFilterOptions{});
  filter.Reset({1, 2, 0.3}, Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  const Eigen::Matrix3d weak = Eigen::Vector3d(1.0, 1.0, 1.0).asDiagonal();  // 1 m, 1 rad
  EXPECT_EQ(filter.Update(weak, Eigen::Vector3d(1, 1, 1)), 0);
  EXPECT_DOUBLE_EQ(filter.Pose().x, 1.0);
  EXPECT_DOUBLE_EQ(filter.Pose().y, 2.0);
  EXPECT_NEAR(filter.PoseCovariance()(0, 0), 0.01, 1e-12);
}

TEST(OdometryFilter, UncalibratedPredictionGrowsLikeARandomWalk) {
  OdometryFilterOptions o;
  o.sigma_xy_per_m = 0.02;
  OdometryFilter filter(o);
  filter.Reset({0, 0, 0}, Eigen::Matrix3d::Identity() * 1e-12);
  for (int k = 0; k < 100; ++k) filter.Predict({0.04, 0, 0});  // 4 m in 4 cm steps
  // Variance 0.02^2 per metre: sigma 4 cm after 4 m, whatever the step length.
  EXPECT_NEAR(std::sqrt(filter.PoseCovariance()(0, 0)), 0.04, 0.002);
  EXPECT_NEAR(filter.Pose().x, 4.0, 1e-9);
  EXPECT_EQ(filter.Calibration(), Eigen::Vector3d(1, 1, 0));
}

}  // namespace
}  // namespace structloc::localisation_core
