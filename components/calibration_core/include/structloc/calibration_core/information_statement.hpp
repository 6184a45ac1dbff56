// What a calibration trajectory determines, in words (thesis 6.5.4 asks for a
// "reasonably complex trajectory"; this says how complex it was): the
// eigen-directions of the parameters' marginal information in units of each
// parameter's deviation limit (the least determined combinations and what
// they mix), and for strongly correlated pairs the combination the data do
// determine (e.g. the ratio of steering gain to axle distance when only the
// curvature per steering tick is seen). DDS-free.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "structloc/calibration_core/calibration_problem.hpp"

namespace structloc::calibration_core {

// `information`: marginal information of the parameters listed in `index`
// (Parameter values, in order); `values`: the estimate; `max_std`: each
// parameter's deviation limit (CalibrationOptions::max_std). One sentence per line.
std::vector<std::string> DescribeInformation(const Eigen::MatrixXd& information,
                                             const std::vector<size_t>& index,
                                             const ParameterValues& values,
                                             const ParameterValues& max_std);

}  // namespace structloc::calibration_core
