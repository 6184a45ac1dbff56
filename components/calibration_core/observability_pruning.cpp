// Observability pruning (see header).
#include "structloc/calibration_core/observability_pruning.hpp"

#include <algorithm>
#include <cmath>

namespace structloc::calibration_core {

std::optional<Parameter> LeastObservable(const ParameterValues& standard_deviation,
                                         const ParameterMask& active,
                                         const ParameterValues& max_standard_deviation) {
  std::optional<Parameter> worst;
  double worst_ratio = 1.0;
  for (size_t k = 0; k < active.size(); ++k) {
    if (!active[k]) continue;
    const double ratio = standard_deviation[k] / max_standard_deviation[k];
    if (!(ratio <= worst_ratio)) {
      worst_ratio = std::isfinite(ratio) ? ratio : 1e300;
      worst = static_cast<Parameter>(k);
    }
  }
  return worst;
}

bool PrunedFit::AnyEstimated() const {
  return std::find(estimated.begin(), estimated.end(), true) != estimated.end();
}

PrunedFit FitObservableParameters(const ParameterMask& requested,
                                  const ParameterValues& max_standard_deviation,
                                  const FitFunction& fit) {
  PrunedFit pruned;
  pruned.estimated = requested;
  while (pruned.AnyEstimated()) {
    pruned.fit = fit(pruned.estimated);
    const auto worst =
        LeastObservable(pruned.fit.standard_deviation, pruned.estimated, max_standard_deviation);
    if (!worst) return pruned;
    pruned.estimated[*worst] = false;
    pruned.not_observable.push_back(*worst);
  }
  return pruned;
}

std::string NotObservableWarning(Parameter p) {
  std::string why;
  if (p == kAxleDistance || p == kSteeringOffset || p == kSteeringGain) {
    why = " (the trajectory turns too little: drive curves both ways)";
  } else if (p == kWheelSeparation) {
    why = " (the trajectory turns too little: turn on the spot or drive curves)";
  } else if (p == kSensorX || p == kSensorY || p == kSensorTheta) {
    why = " (turn on the spot or in tight curves to separate the sensor's mounting)";
  } else {
    why = " (drive longer straight runs)";
  }
  return std::string(ParameterName(p)) + " is not observable from this trajectory" + why +
         ": kept at its nominal value";
}

}  // namespace structloc::calibration_core
