// Observability pruning for the odometry calibration (thesis 6.5.4): a
// parameter the trajectory cannot determine (its standard deviation above the
// limit, e.g. the axle distance from a straight run) is fixed at its nominal
// value and the rest re-estimated without it, worst first, until every
// parameter left is determinable. DDS-free.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "structloc/calibration_core/batch_solver.hpp"
#include "structloc/calibration_core/calibration_problem.hpp"

namespace structloc::calibration_core {

// One estimate of the parameters marked active, the others at nominal.
struct ParameterFit {
  ParameterValues values{};              // every parameter; nominal where not active
  ParameterValues standard_deviation{};  // 0 where not active
  Eigen::MatrixXd covariance;            // among the active parameters, in order
  BatchSolution solution;                // poses, residuals, weights and iterations of the solver
};

// Estimates the parameters marked in the mask (at least one is).
using FitFunction = std::function<ParameterFit(const ParameterMask& active)>;

struct PrunedFit {
  ParameterFit fit;                       // the last fit made (of no use when nothing is estimated)
  ParameterMask estimated{};              // all false when no requested parameter was observable
  std::vector<Parameter> not_observable;  // fixed at nominal, in the order they were dropped
  bool AnyEstimated() const;
};

// The active parameter whose standard deviation exceeds its limit by the
// largest ratio (a non-finite deviation counts as the largest); nullopt when
// every active parameter is within its limit.
std::optional<Parameter> LeastObservable(const ParameterValues& standard_deviation,
                                         const ParameterMask& active,
                                         const ParameterValues& max_standard_deviation);

// Fits the requested parameters, dropping the least observable one and
// refitting until all left are within their limits (or none is left).
PrunedFit FitObservableParameters(const ParameterMask& requested,
                                  const ParameterValues& max_standard_deviation,
                                  const FitFunction& fit);

// The warning for a parameter that was fixed at nominal, with the manoeuvre that would help.
std::string NotObservableWarning(Parameter p);

}  // namespace structloc::calibration_core
