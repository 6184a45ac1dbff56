// Simulator component (see header).
#include "structloc/simulator/simulator_component.hpp"

#include <cmath>
#include <iostream>

#include "structloc/dds_common/diagnostics.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/simulator/sim_conversions.hpp"

namespace structloc::simulator {

SimulatorComponent::SimulatorComponent(dds_common::Node& node,
                                       const simulation_core::Scenario& scenario,
                                       const SimulatorComponentOptions& options)
    : options_(options),
      sim_(scenario),
      scan_(node.CreateWriter<sensor_msgs::msg::LaserScanPubSubType>(dds_common::topics::kScan)),
      odom_(node.CreateWriter<nav_msgs::msg::OdometryPubSubType>(dds_common::topics::kOdom)),
      ground_truth_(
          node.CreateWriter<nav_msgs::msg::OdometryPubSubType>(dds_common::topics::kGroundTruth)),
      encoders_(node.CreateWriter<structloc_msgs::msg::WheelEncodersPubSubType>(
          dds_common::topics::kWheelEncoders)),
      diagnostics_(node.CreateWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
          dds_common::topics::kDiagnostics)),
      tf_static_(
          node.CreateWriter<tf2_msgs::msg::TFMessagePubSubType>(dds_common::topics::kTfStatic)),
      clock_offset_s_(std::floor(dds_common::WallClockSeconds())),
      wall_start_(std::chrono::steady_clock::now()) {
  cmd_vel_ = node.Subscribe<geometry_msgs::msg::TwistPubSubType>(
      dds_common::topics::kCmdVel, [this](const geometry_msgs::msg::Twist& t) {
        if (!std::isfinite(t.linear().x()) || !std::isfinite(t.angular().z())) return;
        std::lock_guard<std::mutex> lock(command_mutex_);
        command_linear_ = t.linear().x();
        command_angular_ = t.angular().z();
      });
  // The laser's mounting, once: rt/tf_static keeps it for late subscribers, as
  // a ROS 2 robot's static transform broadcaster does.
  const geometry::Pose2D& mount = scenario.laser.mount;
  tf2_msgs::msg::TFMessage mounting;
  mounting.transforms().push_back(
      dds_common::ToPlanarTransform(mount.x, mount.y, mount.theta, clock_offset_s_,
                                    options.frames.base_link, options.frames.laser));
  tf_static_.Write(mounting);
  odom_every_ = std::max(1L, std::lround(1.0 / (scenario.odom_rate_hz * scenario.step_s)));
  last_ticks_ = sim_.State().traction_ticks;
  std::cout << "simulator: scenario '" << scenario.name << "' (seed " << scenario.seed << ", "
            << scenario.duration_s << " s), time scale "
            << (options.time_scale > 0 ? std::to_string(options.time_scale) : "as fast as possible")
            << ", clock starts at " << std::fixed << clock_offset_s_ << std::endl;
}

std::chrono::milliseconds SimulatorComponent::Period() const {
  return std::chrono::milliseconds(options_.time_scale > 0 ? 2 : 0);
}

bool SimulatorComponent::Done() const {
  return options_.exit_when_done && sim_.Finished();
}

void SimulatorComponent::Step() {
  if (!started_) {
    const size_t needed = static_cast<size_t>(options_.wait_for_subscribers);
    if (scan_.MatchedReaders() < needed || odom_.MatchedReaders() < needed) return;
    started_ = true;
    // A reader matched here may not have matched this writer yet (discovery
    // is not symmetric in time; with many participants it lags by seconds):
    // the robot first stands at its start, publishing odometry, so that a
    // subscriber that takes its first odometry as the moment of an initial
    // pose takes it at the start, not half a metre on.
    const double settle = needed > 0 ? options_.stand_s : 0.0;
    wall_start_ = std::chrono::steady_clock::now() +
                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double>(settle));
    clock_offset_s_ = std::floor(dds_common::WallClockSeconds() + settle);
    if (needed > 0)
      std::cout << "simulator: subscribers ready, standing at the start for " << settle
                << " s, then starting the clock" << std::endl;
  }
  const auto now = std::chrono::steady_clock::now();
  if (now < wall_start_) {
    PublishStandingStill(std::chrono::duration<double>(wall_start_ - now).count());
    return;
  }
  const double wall = std::chrono::duration<double>(now - wall_start_).count();
  const auto budget_end = now + std::chrono::milliseconds(5);
  {
    std::lock_guard<std::mutex> lock(command_mutex_);
    sim_.CommandVelocity(command_linear_, command_angular_);
  }
  while (!sim_.Finished()) {
    if (options_.time_scale > 0) {
      if (sim_.State().time >= wall * options_.time_scale) break;
    } else if (std::chrono::steady_clock::now() > budget_end) {
      break;
    }
    PublishStep(sim_.Step());
  }
  if (dds_common::WallClockSeconds() - last_diagnostics_wall_s_ >= 1.0) PublishDiagnostics();
}

void SimulatorComponent::PublishStep(const simulation_core::SimState& state) {
  ++steps_;
  distance_ += (state.odometry.Translation() - last_odometry_.Translation()).norm();
  last_odometry_ = state.odometry;
  if (steps_ % odom_every_ == 0) {
    auto encoders = ToWheelEncoders(state, sim_.GetScenario().nominal, last_ticks_, clock_offset_s_,
                                    options_.frames);
    last_ticks_ = state.traction_ticks;
    encoders_.Write(encoders);
    auto odom = ToOdometry(state, distance_, clock_offset_s_, options_.frames);
    odom_.Write(odom);
    auto truth = ToGroundTruth(state, clock_offset_s_, options_.frames);
    ground_truth_.Write(truth);
  }
  if (auto scan = sim_.TakeScan()) {
    auto msg = ToLaserScan(*scan, clock_offset_s_, options_.frames);
    scan_.Write(msg);
    ++scans_published_;
  }
}

void SimulatorComponent::PublishStandingStill(double before_start_s) {
  // On the odometry's own time grid, which the clock's first steps continue.
  const double period = static_cast<double>(odom_every_) * sim_.GetScenario().step_s;
  const double stamp = clock_offset_s_ - std::ceil(before_start_s / period) * period;
  if (stamp < last_standing_stamp_s_ + 0.5 * period) return;
  last_standing_stamp_s_ = stamp;
  odom_.Write(ToOdometry(sim_.State(), 0.0, stamp, options_.frames));
  ground_truth_.Write(ToGroundTruth(sim_.State(), stamp, options_.frames));
}

void SimulatorComponent::PublishDiagnostics() {
  last_diagnostics_wall_s_ = dds_common::WallClockSeconds();
  dds_common::HealthReport report;
  report.message = sim_.Finished() ? "scenario finished" : "simulating";
  report.values = {{"sim_time_s", std::to_string(sim_.State().time)},
                   {"scans_published", std::to_string(scans_published_)},
                   {"scenario", sim_.GetScenario().name}};
  auto diag =
      dds_common::ToDiagnosticArray("simulator", report, clock_offset_s_ + sim_.State().time);
  diagnostics_.Write(diag);
}

}  // namespace structloc::simulator
