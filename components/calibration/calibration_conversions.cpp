// Calibration message conversions (see header).
#include "calibration_conversions.hpp"

#include "ros_conversions.hpp"

namespace structloc::calibration {

EncoderSample FromWheelEncoders(const structloc_msgs::msg::WheelEncoders& msg) {
  return {dds::FromRosTime(msg.header().stamp()), msg.traction_ticks(),
          static_cast<double>(msg.steering_ticks())};
}

Fix FromPoseFix(const geometry_msgs::msg::PoseWithCovarianceStamped& msg) {
  Fix f;
  f.t = dds::FromRosTime(msg.header().stamp());
  const auto& p = msg.pose().pose();
  f.pose = {p.position().x(), p.position().y(), dds::YawFromQuaternion(p.orientation())};
  const auto& c = msg.pose().covariance();
  f.variance = {c[0], c[7], c[35]};
  f.has_variance = f.variance.allFinite() && (f.variance.array() > 0).all();
  return f;
}

namespace {
structloc_msgs::msg::RobotParameters ToMsg(const std::array<double, kParameterCount>& v) {
  structloc_msgs::msg::RobotParameters p;
  p.wheel_radius_m(v[kWheelRadius]);
  p.axle_distance_m(v[kAxleDistance]);
  p.steering_offset_rad(v[kSteeringOffset]);
  p.steering_rad_per_tick(v[kSteeringGain]);
  p.sensor_x_m(v[kSensorX]);
  p.sensor_y_m(v[kSensorY]);
  p.sensor_theta_rad(v[kSensorTheta]);
  return p;
}
}  // namespace

structloc_msgs::msg::CalibrationResult ToCalibrationResult(const CalibrationReport& r,
                                                           double stamp) {
  structloc_msgs::msg::CalibrationResult msg;
  msg.header().stamp(dds::ToRosTime(stamp));
  msg.success(r.success);
  const auto& p = r.parameters;
  msg.parameters(ToMsg({p.wheel_radius, p.axle_distance, p.steering_offset, p.steering_rad_per_tick,
                        p.sensor.x, p.sensor.y, p.sensor.theta}));
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
