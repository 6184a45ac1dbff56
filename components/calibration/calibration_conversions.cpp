// Calibration message conversions (see header).
#include "structloc/calibration/calibration_conversions.hpp"

#include "structloc/calibration_core/calibration_problem.hpp"
#include "structloc/dds_common/ros_conversions.hpp"

namespace structloc::calibration {

calibration_core::EncoderSample FromWheelEncoders(const structloc_msgs::msg::WheelEncoders& msg) {
  calibration_core::EncoderSample s;
  s.t = dds_common::FromRosTime(msg.header().stamp());
  if (msg.differential()) {
    s.left_ticks = msg.left_ticks();
    s.right_ticks = msg.right_ticks();
  } else {
    s.traction_ticks = msg.traction_ticks();
    s.steering_ticks = static_cast<double>(msg.steering_ticks());
  }
  return s;
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
    const std::array<double, calibration_core::kParameterCount>& v, bool differential) {
  structloc_msgs::msg::RobotParameters p;
  p.differential(differential);
  p.left_wheel_radius_m(v[calibration_core::kLeftWheelRadius]);
  p.right_wheel_radius_m(v[calibration_core::kRightWheelRadius]);
  p.wheel_separation_m(v[calibration_core::kWheelSeparation]);
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
    const calibration_core::CalibrationReport& r, double window_start, double window_end) {
  structloc_msgs::msg::CalibrationResult msg;
  msg.header().stamp(dds_common::ToRosTime(window_end));
  msg.window_start(dds_common::ToRosTime(window_start));
  msg.window_end(dds_common::ToRosTime(window_end));
  msg.success(r.success);
  const auto& p = r.parameters;
  const bool differential = p.kind == kinematics::DriveKind::kDifferential;
  msg.parameters(ToMsg(calibration_core::ValuesOf(p), differential));
  msg.standard_deviations(ToMsg(r.standard_deviation, differential));
  for (int k = 0; k < calibration_core::kParameterCount; ++k) {
    if (r.estimated[static_cast<size_t>(k)]) {
      msg.estimated().push_back(
          calibration_core::ParameterName(static_cast<calibration_core::Parameter>(k)));
    }
  }
  if (static_cast<size_t>(r.covariance.rows()) == msg.estimated().size()) {
    for (Eigen::Index a = 0; a < r.covariance.rows(); ++a) {
      for (Eigen::Index b = 0; b < r.covariance.cols(); ++b) {
        msg.covariance().push_back(r.covariance(a, b));
      }
    }
  }
  msg.residual_rms_before(r.residual_rms_before);
  msg.residual_rms_after(r.residual_rms_after);
  msg.fixes_used(static_cast<uint32_t>(r.fixes_used - r.fixes_downweighted));
  msg.fixes_rejected(static_cast<uint32_t>(r.fixes_downweighted));
  for (const auto& w : r.warnings) msg.warnings().push_back(w);
  if (!r.failure.empty()) msg.warnings().push_back("FAILED: " + r.failure);
  for (const auto& cause : r.likely_causes) msg.warnings().push_back("likely cause: " + cause);
  return msg;
}

structloc_msgs::msg::CalibrationResult ToCalibrationResult(
    const calibration_core::OnlineEstimate& e) {
  auto msg = ToCalibrationResult(e.report, e.window_start_s, e.window_end_s);
  for (const auto& change : e.changes) msg.changed().push_back(calibration_core::Describe(change));
  return msg;
}

}  // namespace structloc::calibration
