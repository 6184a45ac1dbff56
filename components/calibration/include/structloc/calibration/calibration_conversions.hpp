// Free conversions between messages and the calibration core (tested without a participant).
#pragma once

#include "geometry_msgs/msg/PoseWithCovarianceStamped.h"
#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc_msgs/msg/CalibrationResult.h"
#include "structloc_msgs/msg/WheelEncoders.h"

namespace structloc::calibration {

calibration_core::EncoderSample FromWheelEncoders(const structloc_msgs::msg::WheelEncoders& msg);
// A fix with the x, y, yaw variances of the message's covariance.
calibration_core::Fix FromPoseFix(const geometry_msgs::msg::PoseWithCovarianceStamped& msg);
structloc_msgs::msg::CalibrationResult ToCalibrationResult(
    const calibration_core::CalibrationReport& report, double stamp);

}  // namespace structloc::calibration
