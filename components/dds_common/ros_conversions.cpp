// ROS 2 field conversions (see header).
#include "structloc/dds_common/ros_conversions.hpp"

#include <cmath>
#include <cstdint>

namespace structloc::dds_common {

builtin_interfaces::msg::Time ToRosTime(double seconds) {
  builtin_interfaces::msg::Time t;
  double whole = std::floor(seconds);
  auto nanos = static_cast<int64_t>(std::llround((seconds - whole) * 1e9));
  if (nanos >= 1000000000) {
    whole += 1.0;
    nanos -= 1000000000;
  }
  t.sec(static_cast<int32_t>(whole));
  t.nanosec(static_cast<uint32_t>(nanos));
  return t;
}

double FromRosTime(const builtin_interfaces::msg::Time& time) {
  return static_cast<double>(time.sec()) + 1e-9 * static_cast<double>(time.nanosec());
}

geometry_msgs::msg::Quaternion ToQuaternion(double yaw_rad) {
  geometry_msgs::msg::Quaternion q;
  q.x(0.0);
  q.y(0.0);
  q.z(std::sin(0.5 * yaw_rad));
  q.w(std::cos(0.5 * yaw_rad));
  return q;
}

double YawFromQuaternion(const geometry_msgs::msg::Quaternion& q) {
  // An uninitialised (all-zero) or scaled quaternion is no rotation: reading a
  // yaw from it would silently turn the robot.
  const double norm2 = q.x() * q.x() + q.y() * q.y() + q.z() * q.z() + q.w() * q.w();
  if (!(std::abs(norm2 - 1.0) <= kQuaternionNormTolerance)) return std::nan("");
  return std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()),
                    1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()));
}

geometry_msgs::msg::TransformStamped ToPlanarTransform(double x, double y, double yaw, double stamp,
                                                       const std::string& parent,
                                                       const std::string& child) {
  geometry_msgs::msg::TransformStamped t;
  t.header().stamp(ToRosTime(stamp));
  t.header().frame_id(parent);
  t.child_frame_id(child);
  t.transform().translation().x(x);
  t.transform().translation().y(y);
  t.transform().rotation(ToQuaternion(yaw));
  return t;
}

}  // namespace structloc::dds_common
