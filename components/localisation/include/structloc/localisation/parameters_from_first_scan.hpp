// Without --params the localisation component chooses its parameters as
// replay does: the shipped laser preset that the first scan's own geometry
// names (localisation_core::ChooseLaserPreset), with the laser's mounting on
// the robot from rt/tf_static (the transforms from base_link to the scan's
// frame, composed in the plane), as a ROS 2 robot's static transform
// broadcaster publishes them; without them, the preset's mounting. One default
// for replay and the component. A pose an operator sends on rt/initialpose
// during the wait is kept for the component.
#pragma once

#include <chrono>
#include <optional>
#include <string>

#include "geometry_msgs/msg/PoseWithCovarianceStamped.h"
#include "structloc/dds_common/component_runtime.hpp"
#include "structloc/geometry/pose2d.hpp"

namespace structloc::localisation {

struct ParametersFromFirstScan {
  std::string file;                       // the preset's path; "" = the built-in defaults
  std::string choice;                     // one line: what was chosen and why
  std::optional<geometry::Pose2D> mount;  // from rt/tf_static, when one was heard
  std::string mount_source;               // one line: where the mounting comes from
  // The newest pose sent on rt/initialpose while the component waited.
  std::optional<geometry_msgs::msg::PoseWithCovarianceStamped> initial_pose;
};

// Waits for the first usable scan on rt/scan (at least two beams, a finite
// non-zero increment), then up to `tf_wait` more for its mounting (the
// transforms from `base_frame` to the scan's frame) when it has not come
// yet. nullopt when `stop` says to stop first. Leaves the node's callbacks
// held, as the component's factory found them.
std::optional<ParametersFromFirstScan> WaitForFirstScan(
    dds_common::Node& node, const dds_common::StopWait& stop, const std::string& base_frame,
    std::chrono::milliseconds tf_wait = std::chrono::milliseconds(1000));

}  // namespace structloc::localisation
