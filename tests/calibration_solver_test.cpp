// The odometry calibration's parts on their own: the robust
// Levenberg-Marquardt solver on small problems with a known answer (a curve
// fit, an outlier that the Huber weights must ignore, an infeasible step it
// must refuse), and the observability pruning that fixes undeterminable
// parameters at nominal (thesis 6.5.4).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "structloc/calibration_core/calibration_report_builder.hpp"
#include "structloc/calibration_core/levenberg_marquardt.hpp"
#include "structloc/calibration_core/observability_pruning.hpp"

namespace structloc::calibration_core {
namespace {

// y = a * exp(b * t) sampled without noise at t = 0, 0.1, ..., 1.9.
struct ExponentialCurve {
  double a = 2.0, b = -1.5;
  std::vector<double> t, y;
  ExponentialCurve() {
    for (int k = 0; k < 20; ++k) {
      t.push_back(0.1 * k);
      y.push_back(a * std::exp(b * t.back()));
    }
  }
  Eigen::VectorXd Residuals(const Eigen::VectorXd& x) const {
    Eigen::VectorXd r(static_cast<Eigen::Index>(t.size()));
    for (size_t k = 0; k < t.size(); ++k) {
      r(static_cast<Eigen::Index>(k)) = y[k] - x(0) * std::exp(x(1) * t[k]);
    }
    return r;
  }
};

LevenbergMarquardtOptions ScalarBlocks() {
  LevenbergMarquardtOptions o;
  o.block_size = 1;
  o.huber_k = 1e9;  // plain least squares unless a test says otherwise
  return o;
}

TEST(LevenbergMarquardt, FitsAnExponentialFromAFarStart) {
  const ExponentialCurve curve;
  const ResidualFunction residual = [&](const Eigen::VectorXd& x) { return curve.Residuals(x); };
  const JacobianFunction jacobian = [&](const Eigen::VectorXd& x) {
    return CentralDifferenceJacobian(residual, x, Eigen::Vector2d(1e-6, 1e-6));
  };
  const auto s = MinimiseRobustly(residual, jacobian, Eigen::Vector2d(1.0, 0.0), ScalarBlocks(),
                                  [](const Eigen::VectorXd&) { return true; });
  EXPECT_NEAR(s.x(0), curve.a, 1e-6);
  EXPECT_NEAR(s.x(1), curve.b, 1e-6);
  EXPECT_LT(s.cost, 1e-12);
  EXPECT_GT(s.iterations, 1);
  EXPECT_LE(s.iterations, ScalarBlocks().max_iterations);
}

TEST(LevenbergMarquardt, CentralDifferencesMatchTheAnalyticJacobian) {
  const ExponentialCurve curve;
  const ResidualFunction residual = [&](const Eigen::VectorXd& x) { return curve.Residuals(x); };
  const Eigen::Vector2d x(1.5, -1.0);
  const Eigen::MatrixXd j = CentralDifferenceJacobian(residual, x, Eigen::Vector2d(1e-6, 1e-6));
  ASSERT_EQ(j.rows(), 20);
  ASSERT_EQ(j.cols(), 2);
  for (size_t k = 0; k < curve.t.size(); ++k) {
    const Eigen::Index row = static_cast<Eigen::Index>(k);
    EXPECT_NEAR(j(row, 0), -std::exp(x(1) * curve.t[k]), 1e-8);
    EXPECT_NEAR(j(row, 1), -x(0) * curve.t[k] * std::exp(x(1) * curve.t[k]), 1e-8);
  }
}

// The mean of 1, 1.1, 0.9, 1.05, 0.95 and a gross outlier of 100.
Eigen::VectorXd MeanResiduals(const Eigen::VectorXd& x) {
  const Eigen::VectorXd data = (Eigen::VectorXd(6) << 1.0, 1.1, 0.9, 1.05, 0.95, 100.0).finished();
  return (data.array() - x(0)).matrix() / 0.1;  // whitened: sigma 0.1
}

TEST(LevenbergMarquardt, HuberWeightsKeepAGrossOutlierFromPullingTheSolution) {
  const ResidualFunction residual = MeanResiduals;
  const JacobianFunction jacobian = [](const Eigen::VectorXd& x) {
    return Eigen::MatrixXd::Constant(6, x.size(), -1.0 / 0.1);
  };
  auto o = ScalarBlocks();
  const auto plain = MinimiseRobustly(residual, jacobian, Eigen::VectorXd::Zero(1), o,
                                      [](const Eigen::VectorXd&) { return true; });
  EXPECT_NEAR(plain.x(0), 17.5, 1e-6);  // least squares: the plain mean
  o.huber_k = 3.0;
  const auto robust = MinimiseRobustly(residual, jacobian, Eigen::VectorXd::Zero(1), o,
                                       [](const Eigen::VectorXd&) { return true; });
  EXPECT_NEAR(robust.x(0), 1.0, 0.1);
  EXPECT_LT(robust.weights(5), 0.01);  // the outlier
  EXPECT_DOUBLE_EQ(robust.weights(0), 1.0);
}

TEST(LevenbergMarquardt, HuberWeightsAreSharedWithinABlock) {
  const Eigen::VectorXd r = (Eigen::VectorXd(6) << 1, 0, 0, 3, 4, 0).finished();
  const Eigen::VectorXd w = HuberWeights(r, 2.5, 3);
  EXPECT_DOUBLE_EQ(w(0), 1.0);
  EXPECT_DOUBLE_EQ(w(2), 1.0);
  for (Eigen::Index k = 3; k < 6; ++k) EXPECT_DOUBLE_EQ(w(k), 0.5);  // norm 5
}

TEST(LevenbergMarquardt, NeverTakesAnInfeasibleStep) {
  // The minimum is at -1, but x must stay positive: it stops short of 0.
  const ResidualFunction residual = [](const Eigen::VectorXd& x) {
    return Eigen::VectorXd::Constant(1, x(0) + 1.0);
  };
  const JacobianFunction jacobian = [](const Eigen::VectorXd&) {
    return Eigen::MatrixXd::Constant(1, 1, 1.0);
  };
  const auto s =
      MinimiseRobustly(residual, jacobian, Eigen::VectorXd::Constant(1, 2.0), ScalarBlocks(),
                       [](const Eigen::VectorXd& x) { return x(0) > 0; });
  EXPECT_GT(s.x(0), 0.0);
  EXPECT_LT(s.x(0), 2.0);
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

TEST(CalibrationReportBuilder, CovarianceIsTheInverseNormalMatrixScaledByTheResiduals) {
  // Two independent parameters, 10 unit-weight residuals each direction.
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(20, 2);
  j.block(0, 0, 10, 1).setConstant(1.0);
  j.block(10, 1, 10, 1).setConstant(2.0);
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(20);
  const Eigen::MatrixXd small = RobustCovariance(j, w, 1.0);  // cost below dof: no scaling
  EXPECT_NEAR(small(0, 0), 0.1, 1e-12);
  EXPECT_NEAR(small(1, 1), 0.025, 1e-12);
  EXPECT_NEAR(small(0, 1), 0.0, 1e-12);
  const Eigen::MatrixXd large = RobustCovariance(j, w, 36.0);  // cost 2x the 18 dof
  EXPECT_NEAR(large(0, 0), 0.2, 1e-12);
  const Eigen::MatrixXd c = Correlation((Eigen::Matrix2d() << 4, 1, 1, 1).finished());
  EXPECT_DOUBLE_EQ(c(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(c(0, 1), 0.5);
}

}  // namespace
}  // namespace structloc::calibration_core
