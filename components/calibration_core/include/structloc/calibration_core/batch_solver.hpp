// The calibration's solver (thesis 6.5.4): robust Levenberg-Marquardt over the
// batch problem's poses and parameters with a sparse Cholesky factorisation
// (Eigen's SimplicialLDLT; the poses form a chain, so the factor stays sparse
// and the work grows linearly with the recording). Each 3-row block (one fix
// or one motion constraint) whose whitened norm exceeds huber_k is
// down-weighted (Huber loss), so a bad fix cannot poison the rest. The
// parameters' marginal information is the Schur complement of the poses in the
// weighted normal matrix. DDS-free.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <vector>

#include "structloc/calibration_core/calibration_problem.hpp"

namespace structloc::calibration_core {

struct BatchSolverOptions {
  int max_iterations = 50;  // Jacobian evaluations at most
  double huber_k = 3.0;     // block norm (in standard deviations) beyond which weights fall
  bool hold_poses = false;  // only the parameters move; the poses stay where they start
};

// Whether candidate parameter values may be taken at all (lengths stay positive).
using FeasibleValues = std::function<bool(const ParameterValues& values)>;

struct BatchSolution {
  CalibrationState state;
  Eigen::VectorXd residuals;  // whitened, at state
  Eigen::VectorXd weights;    // Huber weights, one per residual (equal within a block)
  double cost = 0.0;          // sum of weights * residuals^2
  int iterations = 0;
  bool converged = false;  // the cost stopped falling before max_iterations
  // Marginal information (inverse covariance, before any scaling) of the
  // active parameters, in the order given, from the Huber-weighted Jacobian.
  Eigen::MatrixXd information;
  // Residual rows minus unknowns (at least 1).
  double degrees_of_freedom = 1.0;
};

// Huber weight of every residual from the norm of its 3-row block: 1 up to k, k / norm beyond.
Eigen::VectorXd HuberWeights(const Eigen::VectorXd& residuals, double k);

// Marginal information of the last `parameters` columns of `jacobian` (rows
// already whitened and weighted): H_pp - H_px H_xx^-1 H_xp.
Eigen::MatrixXd MarginalInformation(const Eigen::SparseMatrix<double>& jacobian,
                                    Eigen::Index parameters);

// Marginal information of the parameters listed in `active` at `state`, with
// the blocks weighted by `weights` (HuberWeights; all ones for the plain
// model); with `hold_poses`, the information with the poses known.
Eigen::MatrixXd InformationAt(const CalibrationProblem& problem, const CalibrationState& state,
                              const Eigen::VectorXd& weights, const std::vector<size_t>& active,
                              bool hold_poses = false);

// Minimises the Huber-weighted squared whitened residuals over the poses and
// the parameters listed in `active`, from `start`.
BatchSolution SolveBatch(const CalibrationProblem& problem, const CalibrationState& start,
                         const std::vector<size_t>& active, const BatchSolverOptions& options,
                         const FeasibleValues& feasible);

}  // namespace structloc::calibration_core
