// The odometry calibration's parts on their own (thesis 6.5.4): the batch
// problem's Jacobian, the sparse solver's marginal information, exact data
// giving the exact parameters back, an outlier fix that the Huber weights must
// ignore, the Cramer-Rao bound, the information statement, and the
// observability pruning that fixes undeterminable parameters at nominal.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "structloc/calibration_core/batch_solver.hpp"
#include "structloc/calibration_core/calibration_problem.hpp"
#include "structloc/calibration_core/calibration_report_builder.hpp"
#include "structloc/calibration_core/information_statement.hpp"
#include "structloc/calibration_core/observability_pruning.hpp"
#include "structloc/kinematics/tricycle.hpp"

namespace structloc::calibration_core {
namespace {

// An exact recording of a tricycle driving curves both ways (radius +1 %,
// axle -2 %, steering offset 0.5 deg from nominal): encoders at 100 Hz, fixes
// of a sensor 0.3 m ahead at 10 Hz, all exactly on the true trajectory.
struct ExactDrive {
  kinematics::RobotParameters nominal, truth;
  std::vector<EncoderSample> encoders;
  std::vector<Fix> fixes;
  std::vector<geometry::Pose2D> true_poses;  // the base at each fix
  explicit ExactDrive(double seconds = 60.0) {
    nominal.sensor = {0.3, 0.0, 0.0};
    truth = nominal;
    truth.wheel_radius *= 1.01;
    truth.axle_distance *= 0.98;
    truth.steering_offset = 0.008727;
    const double ticks_per_rad = truth.traction_ticks_per_rev / (2 * geometry::kPi);
    geometry::Pose2D pose;
    double wheel_ticks = 0.0;
    int64_t counted = 0;
    for (int k = 0; k <= static_cast<int>(seconds * 100); ++k) {
      const double t = 0.01 * k;
      const double command =
          0.45 * std::sin(2 * geometry::kPi * t / 40) + 0.15 * std::sin(2 * geometry::kPi * t / 11);
      const double steering_ticks =
          std::round((command - truth.steering_offset) / truth.steering_rad_per_tick);
      if (k > 0) {
        wheel_ticks += 0.7 * 0.01 / truth.wheel_radius * ticks_per_rad;
        const int64_t delta = static_cast<int64_t>(std::floor(wheel_ticks)) - counted;
        counted += delta;
        pose = kinematics::Advance(pose, static_cast<double>(delta) / ticks_per_rad,
                                   truth.SteeringAngle(steering_ticks), truth.wheel_radius,
                                   truth.axle_distance);
      }
      encoders.push_back({t, static_cast<uint64_t>(1000 + counted), steering_ticks});
      if (k % 10 == 5) {
        fixes.push_back({t, geometry::Compose(pose, truth.sensor)});
        true_poses.push_back(pose);
      }
    }
  }
};

CalibrationOptions ExactOptions() {
  CalibrationOptions o;
  o.default_sigma_xy_m = 0.005;
  o.default_sigma_theta_rad = 0.005;
  return o;
}

TEST(BatchSolver, HuberWeightsAreSharedWithinABlock) {
  const Eigen::VectorXd r = (Eigen::VectorXd(6) << 1, 0, 0, 3, 4, 0).finished();
  const Eigen::VectorXd w = HuberWeights(r, 2.5);
  EXPECT_DOUBLE_EQ(w(0), 1.0);
  EXPECT_DOUBLE_EQ(w(2), 1.0);
  for (Eigen::Index k = 3; k < 6; ++k) EXPECT_DOUBLE_EQ(w(k), 0.5);  // norm 5
}

TEST(BatchSolver, MarginalInformationIsTheInverseOfTheParametersCovarianceBlock) {
  std::mt19937 random(3);
  std::normal_distribution<double> unit;
  Eigen::MatrixXd dense(30, 8);
  for (Eigen::Index r = 0; r < dense.rows(); ++r) {
    for (Eigen::Index c = 0; c < dense.cols(); ++c) dense(r, c) = unit(random);
  }
  const Eigen::MatrixXd covariance = (dense.transpose() * dense).inverse();
  const Eigen::MatrixXd information = MarginalInformation(dense.sparseView(), 2);
  const Eigen::MatrixXd expected = covariance.bottomRightCorner(2, 2).inverse();
  EXPECT_LT((information - expected).norm(), 1e-9 * expected.norm());
}

TEST(CalibrationProblem, PoseJacobianMatchesCentralDifferences) {
  const ExactDrive drive(10.0);
  const CalibrationProblem problem(drive.encoders, drive.fixes, drive.nominal, ExactOptions());
  CalibrationState state = problem.Initial();
  for (size_t i = 0; i < state.poses.size(); ++i) state.poses[i].theta += 0.01 * std::sin(i);
  const std::vector<size_t> active{kWheelRadius};
  const Eigen::MatrixXd j = Eigen::MatrixXd(problem.Jacobian(state, active));
  for (Eigen::Index c = 0; c < 12; ++c) {  // the first four poses
    Eigen::VectorXd step = Eigen::VectorXd::Zero(j.cols());
    step(c) = 1e-7;
    const Eigen::VectorXd numeric = (problem.Whitened(problem.Moved(state, step, active)) -
                                     problem.Whitened(problem.Moved(state, -step, active))) /
                                    2e-7;
    EXPECT_LT((numeric - j.col(c)).norm(), 1e-5 * std::max(1.0, numeric.norm())) << "column " << c;
  }
}

TEST(BatchSolver, RecoversTheTrueParametersFromExactData) {
  const ExactDrive drive;
  auto options = ExactOptions();
  options.estimate = {true, true, true, false, true, true, true};
  const auto report = Calibrate(drive.encoders, drive.fixes, drive.nominal, options);
  ASSERT_TRUE(report.success) << report.failure;
  EXPECT_NEAR(report.parameters.wheel_radius, drive.truth.wheel_radius, 1e-7);
  EXPECT_NEAR(report.parameters.axle_distance, drive.truth.axle_distance, 1e-6);
  EXPECT_NEAR(report.parameters.steering_offset, drive.truth.steering_offset, 1e-7);
  EXPECT_NEAR(report.parameters.sensor.x, 0.3, 1e-5);
  EXPECT_LT(report.residual_rms_after, 0.01);
  EXPECT_GT(report.residual_rms_before, 100 * report.residual_rms_after);
  EXPECT_EQ(report.fixes_used, drive.fixes.size());
}

TEST(BatchSolver, AGrossOutlierFixIsDownWeightedAndDoesNotPullTheEstimate) {
  ExactDrive drive;
  drive.fixes[200].pose.x += 1.0;
  const auto report = Calibrate(drive.encoders, drive.fixes, drive.nominal, ExactOptions());
  ASSERT_TRUE(report.success) << report.failure;
  EXPECT_EQ(report.fixes_downweighted, 1u);
  EXPECT_NEAR(report.parameters.wheel_radius, drive.truth.wheel_radius, 2e-6);
  EXPECT_NEAR(report.parameters.axle_distance, drive.truth.axle_distance, 2e-5);
}

TEST(BatchSolver, CramerRaoBoundShrinksWithTheFixNoise) {
  const ExactDrive drive;
  auto options = ExactOptions();
  std::vector<Fix> fixes = drive.fixes;
  const Eigen::MatrixXd coarse =
      CramerRaoCovariance(drive.encoders, fixes, drive.true_poses, drive.truth, options);
  options.default_sigma_xy_m /= 10;
  options.default_sigma_theta_rad /= 10;
  const Eigen::MatrixXd fine =
      CramerRaoCovariance(drive.encoders, fixes, drive.true_poses, drive.truth, options);
  ASSERT_EQ(coarse.rows(), 3);
  for (Eigen::Index k = 0; k < 3; ++k) EXPECT_LT(fine(k, k), coarse(k, k));
}

TEST(InformationStatement, SaysWhichCombinationOfACorrelatedPairIsDetermined) {
  // Gain and axle distance seen only through their ratio, plus a little each.
  ParameterValues values{};
  values[kAxleDistance] = 0.62;
  values[kSteeringGain] = 0.000767;
  CalibrationOptions options;
  Eigen::Vector2d ratio_direction(1.0 / values[kAxleDistance], -1.0 / values[kSteeringGain]);
  Eigen::Matrix2d information = 1e8 * ratio_direction * ratio_direction.transpose();
  information += Eigen::Vector2d(1.0 / (0.05 * 0.05), 1.0 / (1e-4 * 1e-4)).asDiagonal();
  const auto lines =
      DescribeInformation(information, {kAxleDistance, kSteeringGain}, values, options.max_std);
  std::string all;
  for (const auto& l : lines) all += l + "\n";
  EXPECT_NE(all.find("NOT determined"), std::string::npos) << all;
  EXPECT_NE(all.find("axle_distance / steering_rad_per_tick^"), std::string::npos) << all;
  EXPECT_NE(all.find("in effect their ratio"), std::string::npos) << all;
}

TEST(ObservabilityPruning, TheWorstRatioAboveItsLimitIsLeastObservable) {
  const ParameterValues limit{1, 1, 1, 1, 1, 1, 1};
  ParameterMask active{true, true, true, false, false, false, false};
  EXPECT_FALSE(LeastObservable({0.5, 0.9, 1.0, 0, 0, 0, 0}, active, limit).has_value());
  EXPECT_EQ(LeastObservable({2.0, 0.5, 3.0, 0, 0, 0, 0}, active, limit), kSteeringOffset);
  // Only active parameters count, and a non-finite deviation is the worst.
  EXPECT_EQ(LeastObservable({2.0, 0.5, 0.5, 99, 0, 0, 0}, active, limit), kWheelRadius);
  EXPECT_EQ(LeastObservable({1e6, std::nan(""), 0.5, 0, 0, 0, 0}, active, limit), kAxleDistance);
}

// A fit whose parameters' deviations are fixed per parameter; records every call.
struct FakeFit {
  ParameterValues deviation{};
  std::vector<ParameterMask> calls;
  ParameterFit operator()(const ParameterMask& active) {
    calls.push_back(active);
    ParameterFit fit;
    for (size_t k = 0; k < active.size(); ++k) {
      fit.values[k] = static_cast<double>(k);
      if (active[k]) fit.standard_deviation[k] = deviation[k];
    }
    return fit;
  }
};

TEST(ObservabilityPruning, UndeterminableParametersAreDroppedWorstFirstAndTheRestRefitted) {
  FakeFit fake;
  fake.deviation = {0.001, 0.05, 0.1, 0, 0, 0, 0};  // axle 2.5x its limit, offset 5.7x
  CalibrationOptions options;
  const auto pruned = FitObservableParameters(options.estimate, options.max_std, std::ref(fake));
  ASSERT_TRUE(pruned.AnyEstimated());
  EXPECT_EQ(pruned.not_observable, (std::vector<Parameter>{kSteeringOffset, kAxleDistance}));
  EXPECT_EQ(pruned.estimated, (ParameterMask{true, false, false, false, false, false, false}));
  ASSERT_EQ(fake.calls.size(), 3u);
  EXPECT_EQ(fake.calls.back(), pruned.estimated);
  EXPECT_DOUBLE_EQ(pruned.fit.standard_deviation[kWheelRadius], 0.001);
  EXPECT_NE(NotObservableWarning(kAxleDistance).find("axle_distance is not observable"),
            std::string::npos);
}

TEST(ObservabilityPruning, NothingObservableLeavesNothingEstimated) {
  FakeFit fake;
  fake.deviation.fill(1e9);
  CalibrationOptions options;
  const auto pruned = FitObservableParameters(options.estimate, options.max_std, std::ref(fake));
  EXPECT_FALSE(pruned.AnyEstimated());
  EXPECT_EQ(pruned.not_observable.size(), 3u);
}

TEST(CalibrationReportBuilder, CovarianceIsTheInverseInformationScaledByTheResiduals) {
  const Eigen::Matrix2d information = Eigen::Vector2d(10.0, 40.0).asDiagonal();
  const Eigen::MatrixXd small = CovarianceFromInformation(information, 1.0, 18.0);  // no scaling
  EXPECT_NEAR(small(0, 0), 0.1, 1e-12);
  EXPECT_NEAR(small(1, 1), 0.025, 1e-12);
  EXPECT_NEAR(small(0, 1), 0.0, 1e-12);
  const Eigen::MatrixXd large = CovarianceFromInformation(information, 36.0, 18.0);  // 2x the dof
  EXPECT_NEAR(large(0, 0), 0.2, 1e-12);
  const Eigen::MatrixXd c = Correlation((Eigen::Matrix2d() << 4, 1, 1, 1).finished());
  EXPECT_DOUBLE_EQ(c(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(c(0, 1), 0.5);
}

}  // namespace
}  // namespace structloc::calibration_core
