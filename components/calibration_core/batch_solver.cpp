// The calibration's sparse robust solver (see header).
#include "structloc/calibration_core/batch_solver.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

namespace structloc::calibration_core {

Eigen::VectorXd HuberWeights(const Eigen::VectorXd& residuals, double k) {
  Eigen::VectorXd w(residuals.size());
  for (Eigen::Index i = 0; i + 2 < residuals.size(); i += 3) {
    const double n = residuals.segment<3>(i).norm();
    w.segment<3>(i).setConstant(n <= k ? 1.0 : k / n);
  }
  return w;
}

Eigen::MatrixXd MarginalInformation(const Eigen::SparseMatrix<double>& jacobian,
                                    Eigen::Index parameters) {
  const Eigen::Index n = jacobian.cols() - parameters;
  if (parameters == 0) return Eigen::MatrixXd(0, 0);
  const Eigen::SparseMatrix<double> h = jacobian.transpose() * jacobian;
  if (n == 0) return Eigen::MatrixXd(h);
  const Eigen::SparseMatrix<double> hxx = h.topLeftCorner(n, n);
  const Eigen::MatrixXd hxp = Eigen::MatrixXd(h.topRightCorner(n, parameters));
  const Eigen::MatrixXd hpp = Eigen::MatrixXd(h.bottomRightCorner(parameters, parameters));
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(hxx);
  if (ldlt.info() != Eigen::Success) return hpp;
  const Eigen::MatrixXd y = ldlt.solve(hxp);
  const Eigen::MatrixXd s = hpp - hxp.transpose() * y;
  return 0.5 * (s + s.transpose());
}

namespace {

double Cost(const Eigen::VectorXd& residuals, const Eigen::VectorXd& weights) {
  return (weights.array() * residuals.array().square()).sum();
}

// The Jacobian's rows weighted; only its parameter columns when the poses are held.
Eigen::SparseMatrix<double> Weighted(const Eigen::SparseMatrix<double>& jacobian,
                                     const Eigen::VectorXd& weights, bool hold_poses,
                                     Eigen::Index parameters) {
  // Row scaling in place: Eigen's diagonal-times-sparse product into a
  // column-major matrix moves the stored entries once per row (quadratic).
  Eigen::SparseMatrix<double> j =
      hold_poses ? Eigen::SparseMatrix<double>(jacobian.rightCols(parameters)) : jacobian;
  const Eigen::VectorXd scale = weights.cwiseSqrt();
  for (Eigen::Index c = 0; c < j.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(j, c); it; ++it) {
      it.valueRef() *= scale(it.row());
    }
  }
  return j;
}

}  // namespace

BatchSolution SolveBatch(const CalibrationProblem& problem, const CalibrationState& start,
                         const std::vector<size_t>& active, const BatchSolverOptions& options,
                         const FeasibleValues& feasible) {
  BatchSolution s;
  s.state = start;
  s.residuals = problem.Whitened(s.state);
  s.weights = HuberWeights(s.residuals, options.huber_k);
  s.cost = Cost(s.residuals, s.weights);
  double lambda = 1e-4;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  Eigen::Index analysed_nonzeros = -1;
  const auto m = static_cast<Eigen::Index>(active.size());
  const Eigen::Index poses = static_cast<Eigen::Index>(3 * problem.FixCount());
  int it = 0;
  for (; it < options.max_iterations; ++it) {
    const Eigen::SparseMatrix<double> j =
        Weighted(problem.Jacobian(s.state, active), s.weights, options.hold_poses, m);
    const Eigen::VectorXd rw = s.weights.cwiseSqrt().cwiseProduct(s.residuals);
    const Eigen::SparseMatrix<double> h = j.transpose() * j;
    const Eigen::VectorXd g = j.transpose() * rw;
    // Damped in place on the diagonal (every pose and parameter column has
    // entries, so it is structurally full). The Jacobian's pattern does not
    // depend on the values, so the fill-reducing ordering is computed once.
    const Eigen::VectorXd h_diagonal = h.diagonal();
    const Eigen::VectorXd damping = h_diagonal.cwiseMax(1e-12);
    Eigen::SparseMatrix<double> damped = h;
    if (damped.nonZeros() != analysed_nonzeros) {
      ldlt.analyzePattern(damped);
      analysed_nonzeros = damped.nonZeros();
    }
    bool improved = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      damped.diagonal() = h_diagonal + lambda * damping;
      ldlt.factorize(damped);
      Eigen::VectorXd delta = -ldlt.solve(g);
      if (options.hold_poses) {
        delta.conservativeResize(poses + m);
        delta.tail(m) = delta.head(m).eval();
        delta.head(poses).setZero();
      }
      const CalibrationState candidate = problem.Moved(s.state, delta, active);
      if (ldlt.info() != Eigen::Success || !delta.allFinite() || !feasible(candidate.values)) {
        lambda *= 10;
        continue;
      }
      const Eigen::VectorXd rc = problem.Whitened(candidate);
      const Eigen::VectorXd wc = HuberWeights(rc, options.huber_k);
      const double cc = Cost(rc, wc);
      if (cc < s.cost) {
        const double gain = (s.cost - cc) / std::max(s.cost, 1e-300);
        s.state = candidate;
        s.residuals = rc;
        s.weights = wc;
        s.cost = cc;
        lambda = std::max(lambda / 10, 1e-12);
        improved = gain >= 1e-10;  // converged when the cost stops falling
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  s.converged = it < options.max_iterations;
  s.iterations = std::min(it + 1, options.max_iterations);
  s.information = InformationAt(problem, s.state, s.weights, active, options.hold_poses);
  const double unknowns = static_cast<double>(m + (options.hold_poses ? 0 : poses));
  s.degrees_of_freedom = std::max(1.0, static_cast<double>(s.residuals.size()) - unknowns);
  return s;
}

Eigen::MatrixXd InformationAt(const CalibrationProblem& problem, const CalibrationState& state,
                              const Eigen::VectorXd& weights, const std::vector<size_t>& active,
                              bool hold_poses) {
  const auto m = static_cast<Eigen::Index>(active.size());
  return MarginalInformation(Weighted(problem.Jacobian(state, active), weights, hold_poses, m), m);
}

}  // namespace structloc::calibration_core
