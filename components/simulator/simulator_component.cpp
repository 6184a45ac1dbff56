// Simulator component (see header).
#include "simulator_component.hpp"

#include "diagnostics.hpp"
#include "ros_conversions.hpp"

namespace structloc::simulator {
namespace {
nav_msgs::msg::Odometry StandingStill(double stamp, const char* frame) {
  nav_msgs::msg::Odometry odom;
  odom.header().stamp(dds::ToRosTime(stamp));
  odom.header().frame_id(frame);
  odom.child_frame_id("base_link");
  odom.pose().pose().orientation(dds::ToQuaternion(0.0));
  return odom;
}
}  // namespace

SimulatorComponent::SimulatorComponent(dds::Node& node, const SimulatorComponentOptions& options)
    : options_(options),
      odom_(node.CreateWriter<nav_msgs::msg::OdometryPubSubType>(dds::topics::kOdom)),
      ground_truth_(
          node.CreateWriter<nav_msgs::msg::OdometryPubSubType>(dds::topics::kGroundTruth)),
      encoders_(node.CreateWriter<structloc_msgs::msg::WheelEncodersPubSubType>(
          dds::topics::kWheelEncoders)),
      diagnostics_(node.CreateWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
          dds::topics::kDiagnostics)) {
  node.Subscribe<geometry_msgs::msg::TwistPubSubType>(dds::topics::kCmdVel,
                                                      [](const geometry_msgs::msg::Twist&) {});
}

std::chrono::milliseconds SimulatorComponent::Period() const {
  return std::chrono::milliseconds(static_cast<long>(1000.0 / options_.rate_hz));
}

void SimulatorComponent::Step() {
  const double now = dds::WallClockSeconds();
  auto odom = StandingStill(now, "odom");
  odom_.Write(odom);
  auto truth = StandingStill(now, "map");
  ground_truth_.Write(truth);
  structloc_msgs::msg::WheelEncoders enc;
  enc.header().stamp(dds::ToRosTime(now));
  enc.header().frame_id("base_link");
  enc.traction_counter_bits(32);
  encoders_.Write(enc);
  if (steps_++ % static_cast<uint64_t>(options_.rate_hz) == 0) {
    dds::HealthReport report{dds::HealthLevel::kWarn,
                             "stationary robot: motion and laser simulation not implemented yet",
                             {{"steps", std::to_string(steps_)}}};
    auto diag = dds::ToDiagnosticArray("simulator", report, now);
    diagnostics_.Write(diag);
  }
}

}  // namespace structloc::simulator
