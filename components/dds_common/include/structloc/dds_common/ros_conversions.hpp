// Free conversion functions between ROS 2 message fields and plain values
// (seconds as double, planar yaw), tested without a participant.
#pragma once

#include <string>

#include "builtin_interfaces/msg/Time.h"
#include "geometry_msgs/msg/Quaternion.h"
#include "geometry_msgs/msg/TransformStamped.h"

namespace structloc::dds_common {

// Seconds since the epoch <-> builtin_interfaces/Time (nanosec always < 1e9).
builtin_interfaces::msg::Time ToRosTime(double seconds);
double FromRosTime(const builtin_interfaces::msg::Time& time);

// Planar yaw <-> quaternion about z.
geometry_msgs::msg::Quaternion ToQuaternion(double yaw_rad);
// How far the squared norm of a quaternion may be from 1 (float round-off of
// other stacks; tf2 uses the same tolerance) before it is not a rotation.
constexpr double kQuaternionNormTolerance = 1e-2;
// NaN when `q` is not a unit quaternion (all zero, scaled, non-finite), so that
// the receiver rejects the message instead of reading yaw 0 from it.
double YawFromQuaternion(const geometry_msgs::msg::Quaternion& q);

// A planar transform (x, y in m, yaw in rad) of `child` in `parent` at
// `stamp`, as tf2 carries it (z 0, a rotation about z).
geometry_msgs::msg::TransformStamped ToPlanarTransform(double x, double y, double yaw, double stamp,
                                                       const std::string& parent,
                                                       const std::string& child);

}  // namespace structloc::dds_common
