// Robust Levenberg-Marquardt (see header).
#include "structloc/calibration_core/levenberg_marquardt.hpp"

#include <Eigen/Dense>
#include <algorithm>

namespace structloc::calibration_core {

Eigen::VectorXd HuberWeights(const Eigen::VectorXd& residuals, double k, int block_size) {
  Eigen::VectorXd w(residuals.size());
  for (Eigen::Index i = 0; i + block_size - 1 < residuals.size(); i += block_size) {
    const double n = residuals.segment(i, block_size).norm();
    w.segment(i, block_size).setConstant(n <= k ? 1.0 : k / n);
  }
  return w;
}

Eigen::MatrixXd CentralDifferenceJacobian(const ResidualFunction& residual,
                                          const Eigen::VectorXd& x, const Eigen::VectorXd& steps) {
  Eigen::MatrixXd jacobian;
  for (Eigen::Index c = 0; c < x.size(); ++c) {
    Eigen::VectorXd plus = x, minus = x;
    plus(c) += steps(c);
    minus(c) -= steps(c);
    const Eigen::VectorXd column = (residual(plus) - residual(minus)) / (2 * steps(c));
    if (c == 0) jacobian.resize(column.size(), x.size());
    jacobian.col(c) = column;
  }
  return jacobian;
}

LevenbergMarquardtResult MinimiseRobustly(const ResidualFunction& residual,
                                          const JacobianFunction& jacobian,
                                          const Eigen::VectorXd& x0,
                                          const LevenbergMarquardtOptions& options,
                                          const FeasibleFunction& feasible) {
  LevenbergMarquardtResult s;
  s.x = x0;
  s.residuals = residual(s.x);
  s.weights = HuberWeights(s.residuals, options.huber_k, options.block_size);
  s.cost = (s.weights.array() * s.residuals.array().square()).sum();
  double lambda = 1e-3;
  int it = 0;
  for (; it < options.max_iterations; ++it) {
    const Eigen::MatrixXd j = jacobian(s.x);
    const Eigen::MatrixXd h = j.transpose() * s.weights.asDiagonal() * j;
    const Eigen::VectorXd g = j.transpose() * (s.weights.array() * s.residuals.array()).matrix();
    bool improved = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      Eigen::MatrixXd damped = h;
      damped.diagonal() += lambda * h.diagonal().cwiseMax(1e-12);
      const Eigen::VectorXd delta = -damped.ldlt().solve(g);
      const Eigen::VectorXd candidate = s.x + delta;
      if (!delta.allFinite() || !feasible(candidate)) {
        lambda *= 10;
        continue;
      }
      const Eigen::VectorXd rc = residual(candidate);
      const Eigen::VectorXd wc = HuberWeights(rc, options.huber_k, options.block_size);
      const double cc = (wc.array() * rc.array().square()).sum();
      if (cc < s.cost) {
        const double gain = (s.cost - cc) / std::max(s.cost, 1e-300);
        s.x = candidate;
        s.residuals = rc;
        s.weights = wc;
        s.cost = cc;
        lambda = std::max(lambda / 10, 1e-9);
        improved = gain >= 1e-12;  // converged when the cost stops falling
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  s.iterations = std::min(it + 1, options.max_iterations);
  return s;
}

}  // namespace structloc::calibration_core
