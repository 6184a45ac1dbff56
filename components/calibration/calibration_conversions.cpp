// Calibration message conversions (see header).
#include "structloc/calibration/calibration_conversions.hpp"

#include "structloc/calibration_core/calibration_problem.hpp"
#include "structloc/dds_common/ros_conversions.hpp"

namespace structloc::calibration {

calibration_core::EncoderSample FromWheelEncoders(const structloc_msgs::msg::WheelEncoders& msg) {
  return {dds_common::FromRosTime(msg.header().stamp()), msg.traction_ticks(),
          static_cast<double>(msg.steering_ticks())};
}

calibration_core::Fix FromPoseFix(const geometry_msgs::msg::PoseWithCovarianceStamped& msg) {
  calibration_core::Fix f;
  f.t = dds_common::FromRosTime(msg.header().stamp());
  const auto& p = msg.pose().pose();
  f.pose = {p.position().x(), p.position().y(), dds_common::YawFromQuaternion(p.orientation())};
  const auto& c = msg.pose().covariance();
  f.variance = {c[0], c[7], c[35]};
  f.has_variance = f.variance.allFinite() && (f.variance.array() > 0).all();
  return f;
}

namespace {
structloc_msgs::msg::RobotParameters ToMsg(
    const std::array<double, calibration_core::kParameterCount>& v) {
  structloc_msgs::msg::RobotParameters p;
  p.wheel_radius_m(v[calibration_core::kWheelRadius]);
  p.axle_distance_m(v[calibration_core::kAxleDistance]);
  p.steering_offset_rad(v[calibration_core::kSteeringOffset]);
  p.steering_rad_per_tick(v[calibration_core::kSteeringGain]);
  p.sensor_x_m(v[calibration_core::kSensorX]);
  p.sensor_y_m(v[calibration_core::kSensorY]);
  p.sensor_theta_rad(v[calibration_core::kSensorTheta]);
  return p;
}
}  // namespace

structloc_msgs::msg::CalibrationResult ToCalibrationResult(
    const calibration_core::CalibrationReport& r, double stamp) {
  structloc_msgs::msg::CalibrationResult msg;
  msg.header().stamp(dds_common::ToRosTime(stamp));
  msg.success(r.success);
  const auto& p = r.parameters;
  msg.parameters(ToMsg(calibration_core::ValuesOf(p)));
  msg.standard_deviations(ToMsg(r.standard_deviation));
  msg.residual_rms_before(r.residual_rms_before);
  msg.residual_rms_after(r.residual_rms_after);
  msg.fixes_used(static_cast<uint32_t>(r.intervals_used));
  msg.fixes_rejected(static_cast<uint32_t>(r.intervals_downweighted + r.intervals_skipped));
  for (const auto& w : r.warnings) msg.warnings().push_back(w);
  if (!r.failure.empty()) msg.warnings().push_back("FAILED: " + r.failure);
  for (const auto& cause : r.likely_causes) msg.warnings().push_back("likely cause: " + cause);
  return msg;
}

}  // namespace structloc::calibration
