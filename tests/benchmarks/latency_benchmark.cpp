// structloc_latency_benchmark [SECONDS] [RATE_HZ] [CSV] [lost|echo|""] [WAKE_US]: latency and
// load of the localisation component over DDS on one host. It starts the real component,
// publishes the office scenario's 1081-beam scans (default 40 Hz) and
// odometry in real time from the simulation core, and prints scan-published
// -> pose-received latency (median, p99, max) in the steady state, from the
// first second on (the first scan waits for the search that confirms the start
// pose, some 90 ms once), and for the whole run beside it; where it goes (the
// localiser's own update, from rt/structloc/status, with its steps' medians
// to set beside the same scans replayed offline, and the rest: transport,
// thread wake-ups, conversions), and the component's CPU use (% of one core,
// from /proc); with CSV, also each scan's stamp, latency and update time
// (to see when the slow ones come). Before and after the run it measures how
// often the machine itself stops a runnable thread (platform_stalls.hpp), the
// floor under any latency tail. With "lost", the component gets the office map
// with three walls of every four left out and the SICK preset (whole-scan check
// on): the map explains too little of the scans, the tracker keeps searching
// locally, and the latency is that of a searching tracker (CSV "" for none).
// With "echo", a process of this benchmark's own stands in for the component
// and answers each scan with a pose at once from its listener: the floor the
// transport alone sets on this host (two DDS hops, the same QoS, no work).
// With WAKE_US, the component runs with --max-cpu-wake-latency-us WAKE_US
// (the echo peer holds the same limit): the latency with the CPUs held awake.
// It prints the limit the kernel held during the run (a limit asked for may be
// refused; another process may hold one).
// Figures only: it asserts nothing.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "benchmarks/platform_stalls.hpp"
#include "benchmarks/process_cpu.hpp"
#include "benchmarks/realtime_feed.hpp"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "pose_argument.hpp"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "structloc/dds_common/node.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/process/cpu_wake_latency.hpp"
#include "structloc/process/shutdown_signal.hpp"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"
#include "test_domains.hpp"

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

namespace {

// The "echo" mode's peer: a pose with the scan's stamp for every scan, written
// from the listener; odometry is heard and dropped. Runs until SIGTERM.
int EchoPeer(int domain, const std::string& qos_file, const char* wake_us) {
  namespace dds_common = structloc::dds_common;
  structloc::process::ShutdownSignal stop;
  std::unique_ptr<structloc::process::CpuWakeLatencyLimit> wake_limit;
  if (*wake_us != '\0') {
    wake_limit = std::make_unique<structloc::process::CpuWakeLatencyLimit>(std::atoi(wake_us));
  }
  dds_common::Node node({"latency_echo", domain, qos_file, "structloc_localhost", "", {}});
  auto pose = node.CreateWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      dds_common::topics::kPose);
  const auto odom = node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
      dds_common::topics::kOdom, [](const nav_msgs::msg::Odometry&) {});
  const auto scans = node.Subscribe<sensor_msgs::msg::LaserScanPubSubType>(
      dds_common::topics::kScan, [&](const sensor_msgs::msg::LaserScan& m) {
        geometry_msgs::msg::PoseWithCovarianceStamped answer;
        answer.header(m.header());
        pose.Write(answer);
      });
  while (!stop.WaitFor(std::chrono::milliseconds(100))) {
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  namespace dds_common = structloc::dds_common;
  if (argc == 5 && std::string(argv[1]) == "echo-peer")
    return EchoPeer(std::atoi(argv[2]), argv[3], argv[4]);
  namespace simulation_core = structloc::simulation_core;
  namespace simulator = structloc::simulator;
  namespace process = structloc::process;
  const double seconds = argc > 1 ? std::atof(argv[1]) : 20.0;
  const double rate = argc > 2 ? std::atof(argv[2]) : 40.0;
  constexpr double kStallProbeS = 3.0;
  constexpr double kStampOffsetS = 1.0e9;  // scan stamps: simulated time + this
  constexpr double kStartUpS = 1.0;        // scans before this (simulated time): start-up
  const auto stalls_before = structloc::testing::MeasurePlatformStalls(kStallProbeS);
  const std::string source = STRUCTLOC_SOURCE_DIR;
  const int domain = structloc::testing::domains::kLatencyBenchmark;
  auto scenario = simulation_core::LoadScenario(source + "/maps/scenarios/office_people.xml");
  scenario.laser.rate_hz = rate;
  scenario.duration_s = seconds;
  dds_common::NodeOptions options{"latency_feeder",      domain, source + "/qos/structloc_qos.xml",
                                  "structloc_localhost", "",     {}};
  dds_common::Node node(options);
  structloc::testing::RealtimeWriters writers{
      node.CreateWriter<sensor_msgs::msg::LaserScanPubSubType>(dds_common::topics::kScan),
      node.CreateWriter<nav_msgs::msg::OdometryPubSubType>(dds_common::topics::kOdom)};
  std::mutex mutex;
  std::map<double, Clock::time_point> sent;
  std::map<double, double> latency_at;  // by scan stamp
  // The localiser's update by scan stamp: in all, ms, and its steps, us
  // (prefilter, line fits, the feature kinds together, solve).
  struct UpdateTimes {
    double total_ms = 0.0;
    std::array<double, 4> steps_us{};
  };
  std::map<double, UpdateTimes> update_at;
  std::map<std::string, int> lost_reasons;  // of the statuses that said lost
  const auto pose_subscription =
      node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
          dds_common::topics::kPose, [&](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
            const auto now = Clock::now();
            std::lock_guard<std::mutex> lock(mutex);
            auto it = sent.find(dds_common::FromRosTime(m.header().stamp()));
            if (it != sent.end()) {
              latency_at[it->first] =
                  std::chrono::duration<double, std::milli>(now - it->second).count();
            }
          });
  const auto status_subscription =
      node.Subscribe<structloc_msgs::msg::LocalisationStatusPubSubType>(
          dds_common::topics::kStatus, [&](const structloc_msgs::msg::LocalisationStatus& m) {
            std::lock_guard<std::mutex> lock(mutex);
            const auto& t = m.timings();
            double features = 0.0;
            for (const auto& kind : t.features()) features += kind.extract_us();
            update_at[dds_common::FromRosTime(m.header().stamp())] = {
                1e-3 * t.total_us(), {t.prefilter_us(), t.line_fit_us(), features, t.solve_us()}};
            if (m.lost()) ++lost_reasons[m.lost_reason()];
          });
  const auto& p = scenario.initial_pose;
  std::vector<std::string> args = {"--domain",       std::to_string(domain),
                                   "--qos",          options.qos_file,
                                   "--initial-pose", structloc::testing::PoseArgument(p)};
  const bool lost = argc > 4 && std::string(argv[4]) == "lost";
  const bool echo = argc > 4 && std::string(argv[4]) == "echo";
  const std::string wake_us = argc > 5 ? argv[5] : "";
  if (!wake_us.empty()) args.insert(args.end(), {"--max-cpu-wake-latency-us", wake_us});
  const std::string half_map =
      "/tmp/structloc_latency_half_map_" + std::to_string(getpid()) + ".xml";
  if (lost) {
    // Three walls of every four of the office left out.
    std::ifstream in(source + "/maps/office_floor.xml");
    std::ofstream out(half_map);
    int walls = 0;
    for (std::string line; std::getline(in, line);) {
      if (line.find("<wall ") != std::string::npos && walls++ % 4 != 0) continue;
      out << line << "\n";
    }
    args.insert(args.end(),
                {"--map", half_map, "--params", source + "/maps/params/sick_lms2xx.xml"});
  } else {
    // Named, as the simulated robot's launch files do: without it the
    // component waits for a first scan to choose its preset and subscribes
    // to odometry only then, while this feeder waits for both readers.
    args.insert(args.end(), {"--params", source + "/maps/params/office_sick.xml"});
  }
  process::ChildProcess loc(
      echo ? "/proc/self/exe" : std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
      echo
          ? std::vector<std::string>{"echo-peer", std::to_string(domain), options.qos_file, wake_us}
          : args);
  while (writers.scans.MatchedReaders() == 0 || writers.odom.MatchedReaders() == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  // What the figures were measured under: a limit asked for may be refused.
  const auto wake_limit = process::CpuWakeLatencyLimit::InForceUs();
  simulation_core::Simulation sim(scenario);
  const auto start = Clock::now();
  const double cpu_start = structloc::testing::CpuSeconds(loc.Pid());
  structloc::testing::FeedInRealTime(sim, writers, kStampOffsetS, [&](double stamp) {
    std::lock_guard<std::mutex> lock(mutex);
    sent[stamp] = Clock::now();
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  const double cpu = structloc::testing::CpuSeconds(loc.Pid()) - cpu_start;
  loc.Stop(std::chrono::seconds(5));
  if (lost) std::remove(half_map.c_str());
  const auto stalls_after = structloc::testing::MeasurePlatformStalls(kStallProbeS);
  std::lock_guard<std::mutex> lock(mutex);
  if (latency_at.empty()) {
    std::printf("no pose received\n");
    return 1;
  }
  // The whole run, the steady state apart, and where the steady state's time
  // goes (the localiser's update, and everything else); with CSV, every
  // scan's figures (update -1 when its status was not received).
  std::ofstream csv;
  if (argc > 3 && *argv[3] != '\0') {
    csv.open(argv[3]);
    csv << "stamp_s,latency_ms,update_ms\n" << std::fixed;
  }
  std::vector<double> whole, steady, update, rest;
  std::array<std::vector<double>, 4> steps;
  for (const auto& [stamp, ms] : latency_at) {
    const auto u = update_at.find(stamp);
    if (csv.is_open())
      csv << stamp - kStampOffsetS << "," << ms << ","
          << (u == update_at.end() ? -1.0 : u->second.total_ms) << "\n";
    whole.push_back(ms);
    if (stamp - kStampOffsetS < kStartUpS) continue;
    steady.push_back(ms);
    if (u == update_at.end()) continue;
    update.push_back(u->second.total_ms);
    rest.push_back(ms - u->second.total_ms);
    for (size_t k = 0; k < steps.size(); ++k) steps[k].push_back(u->second.steps_us[k]);
  }
  std::printf("%.0f Hz, 1081-beam scans, %.0f s: %zu scans sent, %zu poses received\n", rate, wall,
              sent.size(), whole.size());
  auto quantiles = [](std::vector<double> v, const std::string& what) {
    if (v.empty()) return;
    std::sort(v.begin(), v.end());
    auto q = [&](double f) { return v[std::min(v.size() - 1, static_cast<size_t>(f * v.size()))]; };
    std::printf("%s: median %.3f ms, p99 %.3f ms, max %.3f ms\n", what.c_str(), q(0.5), q(0.99),
                v.back());
  };
  quantiles(steady, "scan published -> pose received, steady state (from " +
                        std::to_string(static_cast<int>(kStartUpS)) + " s on, " +
                        std::to_string(steady.size()) + " poses)");
  quantiles(whole, "  the whole run, start-up included");
  quantiles(update, "  of the steady state, the localiser's update");
  // The update's steps, to compare with the same scans replayed offline
  // (structloc replay --timings).
  auto median = [](std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  std::printf(
      "    its steps' medians: prefilter %.1f us, line fits %.1f us, features %.1f us, solve %.1f "
      "us\n",
      median(steps[0]), median(steps[1]), median(steps[2]), median(steps[3]));
  quantiles(rest, "  of the steady state, transport, threads, conversions");
  std::printf("localisation process CPU: %.1f %% of one core\n", 100.0 * cpu / wall);
  if (!wake_limit) {
    std::printf("CPU wake-up limit in force: unknown (%s cannot be read)\n",
                process::CpuWakeLatencyLimit::kDevice);
  } else if (*wake_limit >= process::CpuWakeLatencyLimit::kNoLimitUs) {
    std::printf("CPU wake-up limit in force: none\n");
  } else {
    std::printf("CPU wake-up limit in force: %d us\n", *wake_limit);
  }
  std::printf("statuses received: %zu", update_at.size());
  for (const auto& [reason, count] : lost_reasons) {
    std::printf(", %d lost (%s)", count, reason.c_str());
  }
  std::printf("\n");
  structloc::testing::PrintPlatformStalls("before", stalls_before);
  structloc::testing::PrintPlatformStalls("after", stalls_after);
  return 0;
}
