// Free conversions between messages and the calibration core (tested without a participant).
#pragma once

#include "geometry_msgs/msg/PoseWithCovarianceStamped.h"
#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc/calibration_core/online_calibration.hpp"
#include "structloc_msgs/msg/CalibrationResult.h"
#include "structloc_msgs/msg/WheelEncoders.h"

namespace structloc::calibration {

calibration_core::EncoderSample FromWheelEncoders(const structloc_msgs::msg::WheelEncoders& msg);
// A fix with the x, y, yaw variances of the message's covariance.
calibration_core::Fix FromPoseFix(const geometry_msgs::msg::PoseWithCovarianceStamped& msg);
// An estimate from the encoder samples stamped window_start..window_end
// (the message's stamp is window_end).
structloc_msgs::msg::CalibrationResult ToCalibrationResult(
    const calibration_core::CalibrationReport& report, double window_start, double window_end);
// An online estimate: its window and the changes it flagged.
structloc_msgs::msg::CalibrationResult ToCalibrationResult(
    const calibration_core::OnlineEstimate& estimate);

}  // namespace structloc::calibration
