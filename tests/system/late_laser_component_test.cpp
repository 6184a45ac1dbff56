// A laser stamped late, live over DDS: the simulator stamps, and publishes,
// every scan 0.13 s after it took it (<laser stamp_latency_s>), as a laser on
// a slow serial line is stamped when its readings arrive. The localisation
// component told so (<tracking scan_latency_s>) meets the demo's accuracy bar
// on the office scenario, its poses stamped when the scans were taken; told
// nothing, it misses the bar.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "dds_test_support.hpp"
#include "live_accuracy.hpp"
#include "pose_argument.hpp"
#include "structloc/evaluation/live_evaluator.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = testing::domains::kLateLaser;
constexpr const char* kLatency = "0.13";

// The office scenario with its laser stamped late, written into `temp`.
std::string LateScenario(const testing::TempDir& temp) {
  std::string text = testing::ReadFile(testing::SourcePath("maps/scenarios/office_people.xml"));
  const std::string laser = "<laser ";
  const auto at = text.find(laser);
  EXPECT_NE(at, std::string::npos);
  text.insert(at + laser.size(), std::string("stamp_latency_s=\"") + kLatency + "\" ");
  // Its map and robot files are named relative to the shipped scenario.
  const std::string file = "file=\"";
  for (auto p = text.find(file); p != std::string::npos; p = text.find(file, p + file.size()))
    text.insert(p + file.size(), testing::SourcePath("maps/scenarios") + "/");
  return temp.Write("office_late.xml", text);
}

// The simulator and the localisation (with `params`) over one run: the
// localisation's poses from 1 s after the start against the truth.
replay::TrajectoryError Track(const std::string& scenario_path, const std::string& params) {
  const auto scenario = simulation_core::LoadScenario(scenario_path);
  dds_common::Node observer(testing::TestNodeOptions("late_laser_observer", kDomain));
  evaluation::LiveEvaluator evaluator(observer, scenario.initial_pose);
  process::ChildProcess localisation(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--params", params,
       "--initial-pose", testing::PoseArgument(scenario.initial_pose)});
  process::ChildProcess simulator(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_simulator",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--scenario",
       scenario_path, "--time-scale", "4", "--wait-for-subscribers", "1", "--exit-when-done"});
  const auto code = simulator.WaitExit(120s);
  EXPECT_TRUE(code.has_value() && *code == 0) << simulator.CapturedOutput();
  localisation.Signal(SIGTERM);
  EXPECT_EQ(localisation.WaitExit(testing::kGenerousTimeout), 0) << localisation.CapturedOutput();
  const auto estimate = evaluator.Estimate();
  const auto truth = evaluator.Truth();
  EXPECT_FALSE(truth.empty());
  return testing::ErrorFromOneSecondAfter(estimate, truth,
                                          truth.empty() ? 0.0 : truth.front().stamp);
}

TEST(LateLaserComponent, ToldTheLatencyTheLocalisationMeetsTheDemosBar) {
  const testing::TempDir temp;
  const std::string scenario = LateScenario(temp);
  const std::string told = temp.Write(
      "told.xml", "<localisation_params base=\"" + testing::SimulatedRobotParams() +
                      "\"><tracking scan_latency_s=\"" + kLatency + "\"/></localisation_params>\n");
  const auto with = Track(scenario, told);
  testing::ExpectDemoAccuracy(with, "told the latency");
  const auto without = Track(scenario, testing::SimulatedRobotParams());
  std::printf("not told: %zu poses, RMSE %.2f mm, max %.2f mm\n", without.matched,
              1e3 * without.position_rmse_m, 1e3 * without.position_max_m);
  EXPECT_GT(without.position_rmse_m, 0.01) << "a late laser tracked as if on time should show it";
}

}  // namespace
}  // namespace structloc
