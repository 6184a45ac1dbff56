// Starting the localisation while the robot drives. Restart: kill -9 it
// mid-run, start it again with no initial pose; it resumes from the pose it
// saved. Late start: its command-line initial pose (the robot's start) holds
// for the first odometry it receives, which comes after the robot drove
// most of a metre. Either way it is accurate within 1 s of simulated time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>

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
constexpr int kDomain = testing::domains::kLocalisationRestart;

TEST(LocalisationRestart, ResumesFromTheSavedPoseAfterKill9) {
  const auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  const testing::TempDir temp;
  const std::string state = temp / "pose_state";
  dds_common::Node observer(testing::TestNodeOptions("restart_observer", kDomain));
  evaluation::LiveEvaluator evaluator(observer, scenario.initial_pose);
  const std::vector<std::string> common = {
      "--domain", std::to_string(kDomain),         "--qos",        testing::ShippedQos(),
      "--params", testing::SimulatedRobotParams(), "--state-file", state};
  const auto& p = scenario.initial_pose;
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.begin(), common.begin(), common.end());
    return extra;
  };
  auto first = std::make_unique<process::ChildProcess>(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
      with({"--initial-pose", testing::PoseArgument(p)}));
  process::ChildProcess simulator(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_simulator",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--scenario",
       testing::SourcePath("maps/scenarios/office_people.xml"), "--time-scale", "2",
       "--wait-for-subscribers", "1", "--exit-when-done"});
  // Let it localise for a while (and save its pose), then kill it hard.
  ASSERT_TRUE(testing::WaitUntil([&] { return evaluator.Snapshot().sim_time_s > 12.0; }, 30s));
  ASSERT_TRUE(std::filesystem::exists(state)) << first->CapturedOutput();
  first->Signal(SIGKILL);
  first->WaitExit(testing::kGenerousTimeout);
  first.reset();
  const double killed_at = evaluator.Snapshot().sim_time_s;
  const size_t poses_before = evaluator.Estimate().size();
  process::ChildProcess second(std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
                               with({}));
  ASSERT_TRUE(
      testing::WaitUntil([&] { return evaluator.Estimate().size() > poses_before + 30; }, 30s))
      << second.CapturedOutput();
  EXPECT_NE(second.CapturedOutput().find("resuming from the pose saved"), std::string::npos)
      << second.CapturedOutput();
  // Accuracy after the restart: every pose more than 1 s (simulated) after the
  // first new one is within the accuracy bar.
  const auto estimate = evaluator.Estimate();
  const auto truth = evaluator.Truth();
  const double resumed = estimate[poses_before].stamp;
  const auto e = testing::ErrorFromOneSecondAfter(
      std::vector<log_formats::StampedPose>(estimate.begin() + poses_before, estimate.end()), truth,
      resumed);
  std::printf("killed at t = %.1f s; resumed %.2f s later\n", killed_at,
              resumed - (truth.empty() ? 0 : truth.front().stamp) - killed_at);
  testing::ExpectDemoAccuracy(e, "resumed");
  simulator.Signal(SIGTERM);
  second.Signal(SIGTERM);
  EXPECT_EQ(second.WaitExit(testing::kGenerousTimeout), 0);
}

// The same race as on a lossy network, where the localisation's odometry
// reader matches seconds late: a tracker started a metre from the robot kept
// that metre for the whole run while it called itself localised.
TEST(LocalisationRestart, StartedLateItMendsItsInitialPoseByALocalSearch) {
  const auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  dds_common::Node observer(testing::TestNodeOptions("late_start_observer", kDomain));
  evaluation::LiveEvaluator evaluator(observer, scenario.initial_pose);
  process::ChildProcess simulator(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_simulator",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--scenario",
       testing::SourcePath("maps/scenarios/office_people.xml"), "--time-scale", "1",
       "--exit-when-done"});
  // Started once the robot is 0.6 m on (it reaches the localisation's
  // search window's 2 m only if discovery took seconds).
  const auto& p = scenario.initial_pose;
  ASSERT_TRUE(testing::WaitUntil(
      [&] {
        const auto truth = evaluator.Truth();
        return !truth.empty() &&
               std::hypot(truth.back().pose.x - p.x, truth.back().pose.y - p.y) > 0.6;
      },
      30s));
  process::ChildProcess localisation(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--params",
       testing::SimulatedRobotParams(), "--initial-pose", testing::PoseArgument(p)});
  ASSERT_TRUE(testing::WaitUntil([&] { return evaluator.Estimate().size() > 40; }, 30s))
      << localisation.CapturedOutput();
  const auto estimate = evaluator.Estimate();
  const auto truth = evaluator.Truth();
  const double first = estimate.front().stamp;
  const auto start = std::lower_bound(
      truth.begin(), truth.end(), first,
      [](const log_formats::StampedPose& t, double stamp) { return t.stamp < stamp; });
  ASSERT_NE(start, truth.end());
  const double moved = std::hypot(start->pose.x - p.x, start->pose.y - p.y);
  std::printf("first pose when the robot had moved %.2f m from the given start\n", moved);
  EXPECT_GT(moved, 0.5) << "the robot had not moved far enough to test the late start";
  EXPECT_NE(localisation.CapturedOutput().find("confirmed by a local search"), std::string::npos)
      << localisation.CapturedOutput();
  testing::ExpectDemoAccuracy(testing::ErrorFromOneSecondAfter(estimate, truth, first),
                              "started late");
  simulator.Signal(SIGTERM);
  localisation.Signal(SIGTERM);
  EXPECT_EQ(localisation.WaitExit(testing::kGenerousTimeout), 0);
}

}  // namespace
}  // namespace structloc
