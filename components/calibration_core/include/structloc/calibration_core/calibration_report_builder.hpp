// Turns an odometry calibration fit (thesis 6.5.4) into its report: the
// parameters' covariance from the robust normal matrix, their standard
// deviations and correlations, the outlier count and the warnings, and the
// verdict whether the estimate deserves the name. DDS-free.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/calibration_core/observability_pruning.hpp"
#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc/kinematics/robot_parameters.hpp"

namespace structloc::calibration_core {

// Covariance of the parameters from their marginal information (the Huber-
// weighted normal matrix with the poses eliminated): its inverse (directions
// it does not constrain get a huge variance), scaled up by the cost per degree
// of freedom when the residuals are larger than whitening expects.
Eigen::MatrixXd CovarianceFromInformation(const Eigen::MatrixXd& information, double cost,
                                          double degrees_of_freedom);

// Correlation coefficients from a covariance matrix.
Eigen::MatrixXd Correlation(const Eigen::MatrixXd& covariance);

// Root mean square of a vector; 0 when it is empty.
double Rms(const Eigen::VectorXd& values);

// `value` with `digits` significant digits, for messages.
std::string ShortNumber(double value, int digits = 4);

// Adds the result of the pruned fit to `report`: the parameters (nominal
// where not estimated), deviations, correlations, residual RMS, iterations,
// outliers and the warnings about unobservable parameters and outliers.
void AddFit(CalibrationReport& report, const PrunedFit& pruned,
            const kinematics::RobotParameters& nominal);

// `report` as a failure for `failure`, with what in the inputs probably caused it.
CalibrationReport Fail(CalibrationReport report, const std::vector<EncoderSample>& encoders,
                       const std::vector<Fix>& fixes, const kinematics::RobotParameters& nominal,
                       const std::string& failure);

// Whether an estimate deserves the name: finite residuals, mostly inliers,
// plausible values, and open-loop dead reckoning better than with the nominal
// parameters (an independent check of the relative-motion fit).
CalibrationReport Judge(CalibrationReport report, const std::vector<EncoderSample>& encoders,
                        const std::vector<Fix>& fixes, const kinematics::RobotParameters& nominal,
                        const CalibrationOptions& options);

}  // namespace structloc::calibration_core
