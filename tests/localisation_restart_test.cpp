// Restart: kill -9 the localisation mid-run, start it again with no initial
// pose; it resumes from the pose it saved and is accurate again within 1 s of
// simulated time.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>

#include "dds_test_support.hpp"
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
      "--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--state-file", state};
  const auto& p = scenario.initial_pose;
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.begin(), common.begin(), common.end());
    return extra;
  };
  auto first = std::make_unique<process::ChildProcess>(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
      with({"--initial-pose",
            std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.theta)}));
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
  std::vector<log_formats::StampedPose> after;
  for (size_t i = poses_before; i < estimate.size(); ++i) {
    if (estimate[i].stamp > resumed + 1.0) after.push_back(estimate[i]);
  }
  const auto e = replay::CompareTrajectories(after, truth, 0.011);
  std::printf(
      "killed at t = %.1f s; resumed %.2f s later; after 1 s: %zu poses, RMSE %.2f mm, max %.2f "
      "mm\n",
      killed_at, resumed - (truth.empty() ? 0 : truth.front().stamp) - killed_at, e.matched,
      1e3 * e.position_rmse_m, 1e3 * e.position_max_m);
  ASSERT_GT(e.matched, 10u);
  EXPECT_LE(e.position_max_m, 0.03);
  EXPECT_LE(e.position_rmse_m, 0.01);
  simulator.Signal(SIGTERM);
  second.Signal(SIGTERM);
  EXPECT_EQ(second.WaitExit(testing::kGenerousTimeout), 0);
}

}  // namespace
}  // namespace structloc
