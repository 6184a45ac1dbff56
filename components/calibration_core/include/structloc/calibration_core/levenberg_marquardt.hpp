// A robust Levenberg-Marquardt least-squares solver, generic over the
// residual function and its Jacobian: the odometry calibration (thesis 6.5.4)
// uses it on whitened fix-interval residuals, and its tests on small problems
// with a known answer. Residuals come in blocks (one per measurement); a
// block whose norm exceeds huber_k is down-weighted (Huber loss), so a few
// outlier measurements cannot pull the solution. DDS-free.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace structloc::calibration_core {

struct LevenbergMarquardtOptions {
  int max_iterations = 50;  // Jacobian evaluations at most
  double huber_k = 3.0;     // block norm (in standard deviations) beyond which weights fall
  int block_size = 3;       // residuals per measurement, weighted together
};

using ResidualFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd& x)>;
using JacobianFunction = std::function<Eigen::MatrixXd(const Eigen::VectorXd& x)>;
// Whether a candidate step may be taken at all (e.g. lengths stay positive).
using FeasibleFunction = std::function<bool(const Eigen::VectorXd& x)>;

struct LevenbergMarquardtResult {
  Eigen::VectorXd x;          // the solution
  Eigen::VectorXd residuals;  // at x
  Eigen::VectorXd weights;    // Huber weights at x, one per residual (equal within a block)
  double cost = 0.0;          // sum of weights * residuals^2 at x
  int iterations = 0;
};

// Huber weight of every residual from the norm of its block: 1 up to k, k / norm beyond.
Eigen::VectorXd HuberWeights(const Eigen::VectorXd& residuals, double k, int block_size);

// Jacobian of `residual` at x by central differences with one step per parameter.
Eigen::MatrixXd CentralDifferenceJacobian(const ResidualFunction& residual,
                                          const Eigen::VectorXd& x, const Eigen::VectorXd& steps);

// Minimises the Huber-weighted sum of squared residuals from x0. Each
// iteration re-linearises and tries up to 10 damping factors; it stops when
// no damping lowers the cost, or the relative cost decrease is below 1e-12,
// or after max_iterations.
LevenbergMarquardtResult MinimiseRobustly(const ResidualFunction& residual,
                                          const JacobianFunction& jacobian,
                                          const Eigen::VectorXd& x0,
                                          const LevenbergMarquardtOptions& options,
                                          const FeasibleFunction& feasible);

}  // namespace structloc::calibration_core
