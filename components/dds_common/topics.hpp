// The topic table: every DDS topic structloc uses, with its QoS profile name.
// ROS 2 topics carry ROS 2's "rt/" prefix so ROS 2 nodes see them as /scan etc.
#pragma once

#include <string>

namespace structloc::dds {

struct TopicSpec {
  std::string name;         // DDS topic name
  std::string qos_profile;  // data_writer / data_reader profile in the QoS file
};

namespace topics {
// Sensor streams (simulator or robot drivers -> localisation, calibration).
inline const TopicSpec kScan{"rt/scan", "sensor_data"};
inline const TopicSpec kOdom{"rt/odom", "sensor_data"};
inline const TopicSpec kWheelEncoders{"rt/wheel_encoders", "sensor_data"};
inline const TopicSpec kGroundTruth{"rt/ground_truth", "sensor_data"};
inline const TopicSpec kCmdVel{"rt/cmd_vel", "reliable_state"};
// Localisation outputs and inputs.
inline const TopicSpec kPose{"rt/pose", "reliable_state"};
inline const TopicSpec kInitialPose{"rt/initialpose", "reliable_state"};
inline const TopicSpec kTf{"rt/tf", "reliable_state"};
inline const TopicSpec kFeatures{"rt/structloc/features", "sensor_data"};
inline const TopicSpec kStatus{"rt/structloc/status", "reliable_state"};
// Calibration output: late subscribers still get the last result.
inline const TopicSpec kCalibration{"rt/structloc/calibration", "latched_result"};
// Every component's health.
inline const TopicSpec kDiagnostics{"rt/diagnostics", "reliable_state"};
}  // namespace topics

}  // namespace structloc::dds
