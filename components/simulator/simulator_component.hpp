// The simulator component: publishes the robot's sensor streams (encoders,
// odometry, ground truth) on DDS. Until the simulation core lands (issue 4)
// the robot stands still at the origin and the component says so.
#pragma once

#include <cstdint>

#include "component_runtime.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "geometry_msgs/msg/TwistPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "structloc_msgs/msg/WheelEncodersPubSubTypes.h"

namespace structloc::simulator {

struct SimulatorComponentOptions {
  double rate_hz = 10.0;  // sensor publication rate
};

class SimulatorComponent : public dds::Component {
 public:
  SimulatorComponent(dds::Node& node, const SimulatorComponentOptions& options);
  void Step() override;
  std::chrono::milliseconds Period() const override;

 private:
  SimulatorComponentOptions options_;
  dds::TopicWriter<nav_msgs::msg::OdometryPubSubType> odom_;
  dds::TopicWriter<nav_msgs::msg::OdometryPubSubType> ground_truth_;
  dds::TopicWriter<structloc_msgs::msg::WheelEncodersPubSubType> encoders_;
  dds::TopicWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType> diagnostics_;
  uint64_t steps_ = 0;
};

}  // namespace structloc::simulator
