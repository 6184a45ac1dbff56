// The topics a user deploys against, one row each: the table the reference
// page docs/reference/topics.md is generated from (`structloc topics`), kept
// beside the topic names so that a topic added to one is added to both.
#pragma once

#include <string>
#include <vector>

#include "structloc/dds_common/topics.hpp"

namespace structloc::dds_common {

struct TopicRow {
  const TopicSpec* topic;
  std::string type;  // ROS 2 message type, or structloc_msgs'
  std::string published_by;
  std::string subscribed_by;
};

inline std::vector<TopicRow> TopicTable() {
  using namespace topics;
  return {
      {&kScan, "sensor_msgs/LaserScan", "simulator (or a laser driver)", "localisation"},
      {&kOdom, "nav_msgs/Odometry", "simulator (or the robot base)", "localisation"},
      {&kWheelEncoders, "structloc_msgs/WheelEncoders", "simulator (or the robot base)",
       "calibration"},
      {&kGroundTruth, "nav_msgs/Odometry (frame map)", "simulator", "evaluation tools"},
      {&kCmdVel, "geometry_msgs/Twist", "any client", "simulator"},
      {&kInitialPose, "geometry_msgs/PoseWithCovarianceStamped", "any client", "localisation"},
      {&kReinitializeGlobalLocalization, "std_msgs/Empty", "any client",
       "localisation (locate the robot globally again)"},
      {&kPose, "geometry_msgs/PoseWithCovarianceStamped", "localisation",
       "calibration, any client"},
      {&kTf, "tf2_msgs/TFMessage (map -> odom)", "localisation", "any client"},
      {&kTfStatic, "tf2_msgs/TFMessage (base_link -> ... -> laser: the laser's mounting)",
       "simulator (or a robot's static transform broadcaster)",
       "localisation started without --params, structloc record"},
      {&kFeatures, "structloc_msgs/ScanFeatures", "localisation", "any client"},
      {&kStatus, "structloc_msgs/LocalisationStatus", "localisation", "any client"},
      {&kHypotheses, "geometry_msgs/PoseArray (frame map)",
       "localisation, while it weighs several poses of a robot without one", "any client"},
      {&kCalibration, "structloc_msgs/CalibrationResult", "calibration", "any client"},
      {&kDiagnostics, "diagnostic_msgs/DiagnosticArray", "every component", "any client"},
  };
}

}  // namespace structloc::dds_common
