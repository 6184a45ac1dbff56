// Plays a simulated scenario through real DDS writers in real time, as a
// laser driver and odometry would publish it: odometry every other step (50 Hz
// at the scenarios' 10 ms step) and every scan when the simulated laser
// completes it. Shared by the benchmarks that time or soak the localisation
// component.
#pragma once

#include <chrono>
#include <functional>
#include <thread>

#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "structloc/dds_common/node.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/simulator/sim_conversions.hpp"

namespace structloc::testing {

struct RealtimeWriters {
  dds_common::TopicWriter<sensor_msgs::msg::LaserScanPubSubType> scans;
  dds_common::TopicWriter<nav_msgs::msg::OdometryPubSubType> odom;
};

// Steps `sim` to its end (or until `keep_going` says stop), sleeping so that
// simulated time runs with the wall clock; stamps are simulated time +
// `offset_s`. `on_scan(stamp)` runs just before each scan is written.
inline void FeedInRealTime(
    simulation_core::Simulation& sim, RealtimeWriters& writers, double offset_s,
    const std::function<void(double)>& on_scan,
    const std::function<bool()>& keep_going = [] { return true; }) {
  const auto start = std::chrono::steady_clock::now();
  long steps = 0;
  while (!sim.Finished() && keep_going()) {
    const auto& s = sim.Step();
    if (++steps % 2 == 0) {
      auto o = simulator::ToOdometry(s, 0.0, offset_s);
      writers.odom.Write(o);
    }
    if (auto scan = sim.TakeScan()) {
      auto msg = simulator::ToLaserScan(*scan, offset_s);
      on_scan(dds_common::FromRosTime(msg.header().stamp()));
      writers.scans.Write(msg);
    }
    std::this_thread::sleep_until(start + std::chrono::duration<double>(s.time));
  }
}

}  // namespace structloc::testing
