// The simulator component: runs a scenario of the simulation core and
// publishes what a real robot would (scans, wheel encoders, odometry) plus the
// ground truth, stamped with the simulation clock, in real time or faster
// (time scale); takes rt/cmd_vel in cmd_vel scenarios.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>

#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "geometry_msgs/msg/TwistPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "structloc/dds_common/component_runtime.hpp"
#include "structloc/simulation_core/simulation.hpp"
#include "structloc_msgs/msg/WheelEncodersPubSubTypes.h"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

namespace structloc::simulator {

struct SimulatorComponentOptions {
  double time_scale = 1.0;      // simulated seconds per wall second; 0 = as fast as possible
  bool exit_when_done = false;  // exit (code 0) when the scenario ends
  // Hold the clock until this many readers of rt/scan and rt/odom match, then
  // stand at the start for stand_s publishing odometry before it starts.
  int wait_for_subscribers = 0;
  // Seconds standing at the start after the readers matched (with
  // wait_for_subscribers > 0): a reader matched by this writer may match it
  // only later (on a lossy network, after discovery's retries), and a
  // subscriber that takes its first odometry as the moment of its initial
  // pose must take it at the start.
  double stand_s = 1.0;
  dds_common::FrameIds frames;  // stamped into every header
};

class SimulatorComponent : public dds_common::Component {
 public:
  SimulatorComponent(dds_common::Node& node, const simulation_core::Scenario& scenario,
                     const SimulatorComponentOptions& options);
  void Step() override;
  std::chrono::milliseconds Period() const override;
  bool Done() const override;

 private:
  void PublishStep(const simulation_core::SimState& state);
  // Before the clock starts: odometry and ground truth of the start pose,
  // stamped `before_start_s` ahead of the clock's start.
  void PublishStandingStill(double before_start_s);
  double last_standing_stamp_s_ = -1e300;
  void PublishDiagnostics();

  SimulatorComponentOptions options_;
  simulation_core::Simulation sim_;
  dds_common::TopicWriter<sensor_msgs::msg::LaserScanPubSubType> scan_;
  dds_common::TopicWriter<nav_msgs::msg::OdometryPubSubType> odom_;
  dds_common::TopicWriter<nav_msgs::msg::OdometryPubSubType> ground_truth_;
  dds_common::TopicWriter<structloc_msgs::msg::WheelEncodersPubSubType> encoders_;
  dds_common::TopicWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType> diagnostics_;
  dds_common::TopicWriter<tf2_msgs::msg::TFMessagePubSubType> tf_static_;  // the laser's mounting
  std::mutex command_mutex_;
  double command_linear_ = 0.0, command_angular_ = 0.0;
  double clock_offset_s_;  // message stamp = offset + simulation time
  std::chrono::steady_clock::time_point wall_start_;
  long steps_ = 0;
  long odom_every_ = 1;
  uint64_t last_ticks_ = 0;
  double distance_ = 0.0;
  geometry::Pose2D last_odometry_;
  uint64_t scans_published_ = 0;
  double last_diagnostics_wall_s_ = 0.0;
  bool started_ = false;
  // Last: destroyed first, so no command arrives in a half-destroyed object.
  dds_common::Subscription cmd_vel_;
};

}  // namespace structloc::simulator
