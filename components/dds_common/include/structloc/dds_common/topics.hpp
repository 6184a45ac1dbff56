// The one table of names every component shares: DDS topics with their QoS
// profile, the QoS profile names of the shipped QoS file, and the default
// frame ids. ROS 2 topics carry ROS 2's "rt/" prefix so ROS 2 nodes see them
// as /scan etc. Frame ids are parameters (FrameIds, set from the command line
// the way Nav2's global_frame / odom_frame / robot_base_frame are); the
// defaults here are REP 105's names.
#pragma once

#include <string>

namespace structloc::dds_common {

struct TopicSpec {
  std::string name;         // DDS topic name
  std::string qos_profile;  // data_writer / data_reader profile in the QoS file
};

namespace qos_profiles {
// Best effort, keep last: a late sample is worth less than the next one.
inline const std::string kSensorData = "sensor_data";
// Reliable, volatile: states and commands none of which may be lost.
inline const std::string kReliableState = "reliable_state";
// Reliable, transient local: late subscribers still get the last sample.
inline const std::string kLatchedResult = "latched_result";
}  // namespace qos_profiles

namespace topics {
// Sensor streams (simulator or robot drivers -> localisation, calibration).
inline const TopicSpec kScan{"rt/scan", qos_profiles::kSensorData};
inline const TopicSpec kOdom{"rt/odom", qos_profiles::kSensorData};
inline const TopicSpec kWheelEncoders{"rt/wheel_encoders", qos_profiles::kSensorData};
inline const TopicSpec kGroundTruth{"rt/ground_truth", qos_profiles::kSensorData};
inline const TopicSpec kCmdVel{"rt/cmd_vel", qos_profiles::kReliableState};
// Localisation outputs and inputs.
inline const TopicSpec kPose{"rt/pose", qos_profiles::kReliableState};
inline const TopicSpec kInitialPose{"rt/initialpose", qos_profiles::kReliableState};
// A request to drop the pose and locate the robot globally again (as AMCL's
// reinitialize_global_localization service; std_msgs/Empty).
inline const TopicSpec kReinitializeGlobalLocalization{"rt/reinitialize_global_localization",
                                                       qos_profiles::kReliableState};
inline const TopicSpec kTf{"rt/tf", qos_profiles::kReliableState};
// Transforms that never change (the laser's mounting), kept for late
// subscribers as tf2's static broadcaster does.
inline const TopicSpec kTfStatic{"rt/tf_static", qos_profiles::kLatchedResult};
inline const TopicSpec kFeatures{"rt/structloc/features", qos_profiles::kSensorData};
inline const TopicSpec kStatus{"rt/structloc/status", qos_profiles::kReliableState};
// A robot without a pose: the poses it is still weighing (geometry_msgs/PoseArray).
inline const TopicSpec kHypotheses{"rt/structloc/hypotheses", qos_profiles::kReliableState};
// Calibration output: late subscribers still get the last result.
inline const TopicSpec kCalibration{"rt/structloc/calibration", qos_profiles::kLatchedResult};
// Every component's health.
inline const TopicSpec kDiagnostics{"rt/diagnostics", qos_profiles::kReliableState};
}  // namespace topics

// The frames stamped into headers (REP 105): poses and the map -> odom
// transform in `map`, odometry in `odom` of `base_link`, scans and features
// in `laser`.
struct FrameIds {
  std::string map = "map";
  std::string odom = "odom";
  std::string base_link = "base_link";
  std::string laser = "laser";
};

}  // namespace structloc::dds_common
