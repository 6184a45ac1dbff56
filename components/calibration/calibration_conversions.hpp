// Free conversions between messages and the calibration core (tested without a participant).
#pragma once

#include "calibration_data.hpp"
#include "geometry_msgs/msg/PoseWithCovarianceStamped.h"
#include "odometry_calibration.hpp"
#include "structloc_msgs/msg/CalibrationResult.h"
#include "structloc_msgs/msg/WheelEncoders.h"

namespace structloc::calibration {

EncoderSample FromWheelEncoders(const structloc_msgs::msg::WheelEncoders& msg);
// A fix with the x, y, yaw variances of the message's covariance.
Fix FromPoseFix(const geometry_msgs::msg::PoseWithCovarianceStamped& msg);
structloc_msgs::msg::CalibrationResult ToCalibrationResult(const CalibrationReport& report,
                                                           double stamp);

}  // namespace structloc::calibration
