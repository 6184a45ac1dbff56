// Simulation -> message conversions (see header).
#include "structloc/simulator/sim_conversions.hpp"

#include "structloc/dds_common/ros_conversions.hpp"

namespace structloc::simulator {

sensor_msgs::msg::LaserScan ToLaserScan(const simulation_core::SimScan& scan, double offset,
                                        const dds_common::FrameIds& frames) {
  sensor_msgs::msg::LaserScan msg;
  msg.header().stamp(dds_common::ToRosTime(offset + scan.stamp));
  msg.header().frame_id(frames.laser);
  msg.angle_min(static_cast<float>(scan.angle_min));
  msg.angle_increment(static_cast<float>(scan.angle_increment));
  msg.angle_max(static_cast<float>(
      scan.angle_min + scan.angle_increment * static_cast<double>(scan.ranges.size() - 1)));
  msg.time_increment(static_cast<float>(scan.time_increment));
  msg.scan_time(static_cast<float>(scan.scan_time));
  msg.range_min(static_cast<float>(scan.range_min));
  msg.range_max(static_cast<float>(scan.range_max));
  msg.ranges(scan.ranges);
  return msg;
}

namespace {
nav_msgs::msg::Odometry PoseMessage(const geometry::Pose2D& p, double stamp,
                                    const std::string& frame, const std::string& child_frame) {
  nav_msgs::msg::Odometry msg;
  msg.header().stamp(dds_common::ToRosTime(stamp));
  msg.header().frame_id(frame);
  msg.child_frame_id(child_frame);
  msg.pose().pose().position().x(p.x);
  msg.pose().pose().position().y(p.y);
  msg.pose().pose().orientation(dds_common::ToQuaternion(p.theta));
  return msg;
}
}  // namespace

nav_msgs::msg::Odometry ToOdometry(const simulation_core::SimState& s, double distance_m,
                                   double offset, const dds_common::FrameIds& frames) {
  auto msg = PoseMessage(s.odometry, offset + s.time, frames.odom, frames.base_link);
  msg.twist().twist().linear().x(s.odom_linear);
  msg.twist().twist().angular().z(s.odom_angular);
  // A plain drift model: 2 cm and 0.6 deg per metre driven (1 sigma), plus a floor.
  const double sxy = 0.001 + 0.02 * distance_m, st = 0.001 + 0.0105 * distance_m;
  auto& c = msg.pose().covariance();
  c[0] = c[7] = sxy * sxy;
  c[14] = c[21] = c[28] = 1e6;  // z, roll, pitch: not estimated
  c[35] = st * st;
  return msg;
}

nav_msgs::msg::Odometry ToGroundTruth(const simulation_core::SimState& s, double offset,
                                      const dds_common::FrameIds& frames) {
  return PoseMessage(s.truth, offset + s.time, frames.map, frames.base_link);
}

structloc_msgs::msg::WheelEncoders ToWheelEncoders(const simulation_core::SimState& s,
                                                   const kinematics::RobotParameters& nominal,
                                                   uint64_t previous_ticks, double offset,
                                                   const dds_common::FrameIds& frames) {
  structloc_msgs::msg::WheelEncoders msg;
  msg.header().stamp(dds_common::ToRosTime(offset + s.time));
  msg.header().frame_id(frames.base_link);
  msg.traction_counter_bits(static_cast<uint8_t>(nominal.traction_counter_bits));
  if (nominal.kind == kinematics::DriveKind::kDifferential) {
    msg.differential(true);
    msg.left_ticks(static_cast<uint32_t>(s.left_ticks));
    msg.right_ticks(static_cast<uint32_t>(s.right_ticks));
    return msg;
  }
  msg.traction_ticks(static_cast<uint32_t>(s.traction_ticks));
  msg.steering_ticks(static_cast<int32_t>(s.steering_ticks));
  msg.traction_angle_increment_rad(
      nominal.WheelAngle(nominal.TickDelta(previous_ticks, s.traction_ticks)));
  msg.steering_angle_rad(nominal.SteeringAngle(static_cast<double>(s.steering_ticks)));
  return msg;
}

}  // namespace structloc::simulator
