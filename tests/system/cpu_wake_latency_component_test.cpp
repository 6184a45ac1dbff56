// The localisation component asked to hold the CPUs' wake-up latency: where
// this machine lets it write Linux's PM QoS device, the kernel holds the
// limit while the component runs and drops it when it stops; where not, the
// component says why in its log and its diagnostics and localises all the
// same. The real component over DDS, fed the office scenario.
#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

#include "localisation_feed.hpp"
#include "pose_argument.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/process/cpu_wake_latency.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "test_domains.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

constexpr int kDomain = testing::domains::kCpuWakeLatency;

TEST(CpuWakeLatency, TheComponentHoldsTheLimitOrSaysWhyNotAndLocalisesEitherWay) {
  const std::string device = process::CpuWakeLatencyLimit::kDevice;
  const bool can_hold = ::access(device.c_str(), W_OK) == 0;
  const bool can_read = ::access(device.c_str(), R_OK) == 0;
  auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  scenario.duration_s = 4.0;
  testing::LocalisationFeed feed("wake_limit_feeder", kDomain);
  process::ChildProcess localisation(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--params",
       testing::SimulatedRobotParams(), "--initial-pose",
       testing::PoseArgument(scenario.initial_pose), "--max-cpu-wake-latency-us", "0"});
  ASSERT_TRUE(feed.WaitForLocalisation(testing::kGenerousTimeout)) << localisation.CapturedOutput();
  bool held_while_running = false;
  size_t sent = 0;
  feed.Play(scenario, [&](int, const simulation_core::SimState&, sensor_msgs::msg::LaserScan&) {
    if (can_read && process::CpuWakeLatencyLimit::InForceUs() == 0) held_while_running = true;
    ++sent;
    return true;
  });
  ASSERT_TRUE(testing::WaitUntil([&] { return !feed.Value("cpu_wake_latency").empty(); }))
      << localisation.CapturedOutput();
  const std::string state = feed.Value("cpu_wake_latency");
  const std::string log = localisation.CapturedOutput();
  if (can_hold) {
    EXPECT_EQ(state, "at most 0 us");
    EXPECT_NE(log.find("held to wake within 0 us"), std::string::npos) << log;
    if (can_read) {
      EXPECT_TRUE(held_while_running);
    }
  } else {
    EXPECT_EQ(state.rfind("not limited: cannot limit the CPUs' wake-up latency: " + device, 0), 0u)
        << state;
    EXPECT_NE(log.find("WARNING: cannot limit the CPUs' wake-up latency"), std::string::npos)
        << log;
  }
  // Every scan answered (a few may be dropped for the newest on a loaded machine).
  EXPECT_TRUE(testing::WaitUntil([&] { return feed.Answered() > sent * 4 / 5; }))
      << feed.Answered() << " of " << sent << " answered\n"
      << localisation.CapturedOutput();
  EXPECT_LT(feed.WorstError(), 0.015);
  EXPECT_FALSE(localisation.Poll().has_value()) << log;
  localisation.Stop(std::chrono::seconds(5));
  // No test but this one holds 0 us: once the component is gone, neither does the kernel.
  if (can_hold && can_read) {
    EXPECT_NE(process::CpuWakeLatencyLimit::InForceUs(), 0);
  }
}

}  // namespace
}  // namespace structloc
