// Free conversion functions between ROS 2 message fields and plain values
// (seconds as double, planar yaw), tested without a participant.
#pragma once

#include "builtin_interfaces/msg/Time.h"
#include "geometry_msgs/msg/Quaternion.h"

namespace structloc::dds {

// Seconds since the epoch <-> builtin_interfaces/Time (nanosec always < 1e9).
builtin_interfaces::msg::Time ToRosTime(double seconds);
double FromRosTime(const builtin_interfaces::msg::Time& time);

// Planar yaw <-> quaternion about z.
geometry_msgs::msg::Quaternion ToQuaternion(double yaw_rad);
double YawFromQuaternion(const geometry_msgs::msg::Quaternion& q);

}  // namespace structloc::dds
