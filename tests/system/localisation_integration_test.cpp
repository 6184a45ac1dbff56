// The acceptance run of the localisation: simulator and localisation as
// separate processes over DDS from the real launch file, on the office
// scenario (1 % wheel-radius error, 0.5 deg steering offset, people): position
// RMSE <= 10 mm, max <= 30 mm, heading RMSE <= 0.3 deg, never lost, while
// odometry alone drifts by metres. The same scenario recorded to a CARMEN log
// and replayed offline gives the same accuracy.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "dds_test_support.hpp"
#include "structloc/evaluation/live_evaluator.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/replay/replay.hpp"
#include "structloc/simulation_core/recorder.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = testing::domains::kLocalisationIntegration;
constexpr double kDeg = 180.0 / geometry::kPi;

TEST(LocalisationIntegration, OfficeOverDdsMeetsTheAccuracyBarAndIsNeverLost) {
  const auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  dds_common::Node observer(testing::TestNodeOptions("evaluator", kDomain));
  evaluation::LiveEvaluator evaluator(observer, scenario.initial_pose);
  const testing::TempDir temp;
  const std::string state = temp / "pose_state";
  process::ChildProcess launch(std::string(STRUCTLOC_BIN_DIR) + "/structloc",
                               {"launch", testing::SourcePath("launch_xml/demo.launch.xml"),
                                "domain:=" + std::to_string(kDomain), "time_scale:=4",
                                "state_file:=" + state, "qos:=" + testing::ShippedQos()});
  const auto code = launch.WaitExit(120s);
  ASSERT_TRUE(code.has_value()) << launch.CapturedOutput();
  ASSERT_EQ(*code, 0) << launch.CapturedOutput();
  // No wait for poses still in flight: the figures are over some 600 poses.
  const auto est = evaluator.EstimateError();
  const auto odo = evaluator.OdometryError();
  std::printf(
      "over DDS: %zu poses, RMSE %.2f mm, max %.2f mm, heading RMSE %.4f deg, lost %llu; "
      "odometry only RMSE %.0f mm, max %.0f mm\n",
      est.matched, 1e3 * est.position_rmse_m, 1e3 * est.position_max_m, est.heading_rmse_rad * kDeg,
      static_cast<unsigned long long>(evaluator.LostCount()), 1e3 * odo.position_rmse_m,
      1e3 * odo.position_max_m);
  EXPECT_GT(est.matched, 500u);  // 10 Hz for ~60 s
  EXPECT_LE(est.position_rmse_m, 0.010);
  EXPECT_LE(est.position_max_m, 0.030);
  EXPECT_LE(est.heading_rmse_rad * kDeg, 0.3);
  EXPECT_EQ(evaluator.LostCount(), 0u);
  EXPECT_GT(odo.position_max_m, 1.0);  // odometry alone drifts by metres
}

TEST(LocalisationIntegration, TheSameScenarioReplayedOfflineGivesTheSameAccuracy) {
  const auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  const testing::TempDir temp;
  const std::string dir = temp / "office";
  simulation_core::RecordScenario(scenario, dir);
  replay::ReplayOptions o;
  o.map_path = testing::SourcePath("maps/office_floor.xml");
  o.log_path = dir + "/run.clf";
  o.params_path = testing::SourcePath("maps/params/office_sick.xml");
  o.truth_path = dir + "/truth.tum";
  o.out_tum = dir + "/estimate.tum";
  o.initial_pose = scenario.initial_pose;
  const auto report = replay::RunReplay(o);
  ASSERT_TRUE(report.estimate_error.has_value());
  const auto& e = *report.estimate_error;
  std::printf(
      "replay: %zu scans, RMSE %.2f mm, max %.2f mm, heading RMSE %.4f deg, lost %zu; "
      "odometry only max %.0f mm\n",
      report.scans_used, 1e3 * e.position_rmse_m, 1e3 * e.position_max_m, e.heading_rmse_rad * kDeg,
      report.scans_lost, 1e3 * report.odometry_error->position_max_m);
  EXPECT_GT(report.scans_used, 590u);
  EXPECT_LE(e.position_rmse_m, 0.010);
  EXPECT_LE(e.position_max_m, 0.030);
  EXPECT_LE(e.heading_rmse_rad * kDeg, 0.3);
  EXPECT_EQ(report.scans_lost, 0u);
  EXPECT_GT(report.odometry_error->position_max_m, 1.0);
}

}  // namespace
}  // namespace structloc
