// ROS 2 namespaces for a component's topics, so that several robots share one
// DDS domain: in namespace `robot1` every topic rt/X of the topics table (and
// any topic name given on the command line) becomes rt/robot1/X, as a ROS 2
// node started with `--ros-args -r __ns:=/robot1` publishes /robot1/scan.
// rt/tf and rt/diagnostics move too (as in Nav2's multi-robot bringup, which
// remaps /tf into each robot's namespace), so one robot's map -> odom never
// reaches another's listeners.
#pragma once

#include <string>

#include "structloc/dds_common/topics.hpp"

namespace structloc::dds_common {

// `ns` without its leading and trailing '/' ("/robot1/" -> "robot1", "" and
// "/" -> ""); throws config::ConfigError naming the namespace unless every
// '/'-separated token starts with a letter or '_' and holds only letters,
// digits and '_' (ROS 2's name rules).
std::string NormaliseNamespace(const std::string& ns);

// `topic` inside the (normalised) namespace `ns`: "rt/scan" -> "rt/robot1/scan";
// unchanged for "" and for a name without the rt/ prefix.
TopicSpec InNamespace(const TopicSpec& topic, const std::string& ns);

}  // namespace structloc::dds_common
