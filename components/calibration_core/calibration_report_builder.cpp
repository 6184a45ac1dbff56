// The calibration report from a fit (see header).
#include "structloc/calibration_core/calibration_report_builder.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "structloc/calibration_core/calibration_diagnosis.hpp"

namespace structloc::calibration_core {

Eigen::MatrixXd CovarianceFromInformation(const Eigen::MatrixXd& information, double cost,
                                          double degrees_of_freedom) {
  const double scale = std::max(1.0, cost / std::max(1.0, degrees_of_freedom));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(information);
  const double largest = eig.eigenvalues().maxCoeff();
  Eigen::VectorXd inv = eig.eigenvalues();
  for (Eigen::Index k = 0; k < inv.size(); ++k)
    inv(k) = inv(k) > 1e-12 * largest ? 1.0 / inv(k) : 1e300;
  return scale * eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

Eigen::MatrixXd Correlation(const Eigen::MatrixXd& covariance) {
  const Eigen::Index n = covariance.rows();
  Eigen::MatrixXd correlation = Eigen::MatrixXd::Identity(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    for (Eigen::Index b = 0; b < n; ++b) {
      correlation(a, b) = covariance(a, b) / std::sqrt(covariance(a, a) * covariance(b, b));
    }
  }
  return correlation;
}

double Rms(const Eigen::VectorXd& values) {
  return values.size() ? std::sqrt(values.squaredNorm() / static_cast<double>(values.size())) : 0.0;
}

std::string ShortNumber(double value, int digits) {
  std::ostringstream out;
  out << std::setprecision(digits) << value;
  return out.str();
}

void AddFit(CalibrationReport& report, const PrunedFit& pruned,
            const kinematics::RobotParameters& nominal) {
  for (const Parameter p : pruned.not_observable) {
    report.warnings.push_back(NotObservableWarning(p));
  }
  const ParameterFit& fit = pruned.fit;
  report.iterations = fit.solution.iterations;
  if (!pruned.AnyEstimated()) return;
  if (!fit.solution.converged) {
    report.warnings.push_back("the solver stopped at its limit of " +
                              std::to_string(fit.solution.iterations) +
                              " iterations before converging: the estimate may still move");
  }
  report.parameters = WithValues(nominal, fit.values);
  report.estimated = pruned.estimated;
  report.standard_deviation = fit.standard_deviation;
  report.covariance = fit.covariance;
  report.correlation = Correlation(fit.covariance);
  const Eigen::VectorXd& r = fit.solution.residuals;
  // Blocks: one per fix, then one per fix interval.
  for (Eigen::Index k = 0; k + 2 < r.size(); k += 3) {
    if (fit.solution.weights(k) >= 0.5) continue;
    if (static_cast<size_t>(k / 3) < report.fixes_used) {
      ++report.fixes_downweighted;
    } else {
      ++report.intervals_downweighted;
    }
  }
  if (report.fixes_downweighted + report.intervals_downweighted > 0) {
    report.warnings.push_back(std::to_string(report.fixes_downweighted) + " fixes and " +
                              std::to_string(report.intervals_downweighted) +
                              " fix intervals look like outliers and were down-weighted");
  }
}

CalibrationReport Fail(CalibrationReport report, const std::vector<EncoderSample>& encoders,
                       const std::vector<Fix>& fixes, const kinematics::RobotParameters& nominal,
                       const std::string& failure) {
  report.success = false;
  report.failure = failure;
  report.likely_causes = LikelyCauses(encoders, fixes, nominal);
  return report;
}

CalibrationReport Judge(CalibrationReport report, const std::vector<EncoderSample>& encoders,
                        const std::vector<Fix>& fixes, const kinematics::RobotParameters& nominal,
                        const CalibrationOptions& options) {
  if (!std::isfinite(report.residual_rms_after)) {
    return Fail(std::move(report), encoders, fixes, nominal,
                "the residuals with the estimated parameters are not finite");
  }
  // Either kind of block mostly outlying means the model does not explain the data.
  const double fix_fraction = static_cast<double>(report.fixes_downweighted) /
                              static_cast<double>(std::max<size_t>(1, report.fixes_used));
  const double interval_fraction = static_cast<double>(report.intervals_downweighted) /
                                   static_cast<double>(std::max<size_t>(1, report.intervals_used));
  if (std::max(fix_fraction, interval_fraction) > options.max_outlier_fraction) {
    return Fail(
        std::move(report), encoders, fixes, nominal,
        std::to_string(report.fixes_downweighted) + " of " + std::to_string(report.fixes_used) +
            " fixes and " + std::to_string(report.intervals_downweighted) + " of " +
            std::to_string(report.intervals_used) + " fix intervals are outliers (more than " +
            ShortNumber(100 * options.max_outlier_fraction) +
            " % of either): the odometry model does not explain the fixes");
  }
  try {
    report.parameters.Validate();
  } catch (const std::invalid_argument& e) {
    return Fail(std::move(report), encoders, fixes, nominal,
                std::string("the estimate is implausible: ") + e.what());
  }
  report.dead_reckoning_rms_nominal = DeadReckoningRms(encoders, fixes, nominal);
  report.dead_reckoning_rms_calibrated = DeadReckoningRms(encoders, fixes, report.parameters);
  // Equal is fine: re-calibrating a calibrated robot confirms its parameters
  // (within their uncertainty, hence the tolerance).
  if (!(report.dead_reckoning_rms_calibrated <= options.max_dead_reckoning_ratio *
                                                    (1 + options.dead_reckoning_tolerance) *
                                                    report.dead_reckoning_rms_nominal)) {
    return Fail(std::move(report), encoders, fixes, nominal,
                "dead reckoning with the estimate is worse than with the nominal "
                "parameters (RMS against the fixes " +
                    ShortNumber(report.dead_reckoning_rms_calibrated) + " m calibrated, " +
                    ShortNumber(report.dead_reckoning_rms_nominal) + " m nominal)");
  }
  report.success = true;
  return report;
}

}  // namespace structloc::calibration_core
