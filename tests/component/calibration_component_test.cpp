// The live calibration over DDS: simulator (known parameter errors),
// localisation (fixes on rt/pose with covariances) and calibration as
// separate processes. After recording, the result is published RELIABLE +
// TRANSIENT_LOCAL: a subscriber that joins afterwards still receives it, also
// after the component was restarted, and its values meet the accuracy bars.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>

#include "dds_test_support.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "pose_argument.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "structloc_msgs/msg/CalibrationResultPubSubTypes.h"
#include "temp_dir.hpp"
#include "test_domains.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = testing::domains::kCalibrationComponent;

// Simulator, localisation and calibration (with `calibration_args`) as
// separate processes on the scenario; `until` is checked on every
// CalibrationResult received from the start (under the lock) until it says
// the run has seen enough or 60 s pass; then `while_running` runs, the
// processes still up.
struct LiveRun {
  std::vector<structloc_msgs::msg::CalibrationResult> results;  // in arrival order
  std::string calibration_state;                                // newest diagnostics message
  std::string output;
  bool finished = false;
};

LiveRun RunLive(
    const std::string& scenario_file, std::vector<std::string> calibration_args,
    const std::function<bool(const LiveRun&)>& until,
    const std::function<void()>& while_running = [] {}) {
  const auto scenario = simulation_core::LoadScenario(testing::SourcePath(scenario_file));
  dds_common::Node observer(testing::TestNodeOptions("cal_observer", kDomain));
  std::mutex mutex;
  LiveRun run;
  const auto diagnostics_subscription =
      observer.Subscribe<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
          dds_common::topics::kDiagnostics, [&](const diagnostic_msgs::msg::DiagnosticArray& a) {
            std::lock_guard<std::mutex> lock(mutex);
            for (const auto& s : a.status()) {
              if (s.name() == "structloc/calibration") run.calibration_state = s.message();
            }
          });
  const auto result_subscription =
      observer.Subscribe<structloc_msgs::msg::CalibrationResultPubSubType>(
          dds_common::topics::kCalibration, [&](const structloc_msgs::msg::CalibrationResult& r) {
            std::lock_guard<std::mutex> lock(mutex);
            run.results.push_back(r);
          });
  const std::vector<std::string> common = {"--domain", std::to_string(kDomain), "--qos",
                                           testing::ShippedQos()};
  auto args = [&](std::vector<std::string> extra) {
    extra.insert(extra.begin(), common.begin(), common.end());
    return extra;
  };
  const std::string bin = STRUCTLOC_BIN_DIR;
  const auto& p = scenario.initial_pose;
  process::ChildProcess calibration(bin + "/structloc_calibration", args(calibration_args));
  process::ChildProcess localisation(bin + "/structloc_localisation",
                                     args({"--initial-pose", testing::PoseArgument(p), "--params",
                                           testing::SimulatedRobotParams()}));
  process::ChildProcess simulator(
      bin + "/structloc_simulator",
      args({"--scenario", testing::SourcePath(scenario_file), "--time-scale", "8",
            "--wait-for-subscribers", "1", "--exit-when-done"}));
  run.finished = testing::WaitUntil(
      [&] {
        std::lock_guard<std::mutex> lock(mutex);
        return until(run);
      },
      60s);
  if (run.finished) while_running();
  std::lock_guard<std::mutex> lock(mutex);
  run.output = calibration.CapturedOutput();
  return run;
}

bool Calibrated(const LiveRun& run) {
  return run.calibration_state.rfind("calibrat", 0) == 0 && run.calibration_state != "calibrating";
}

// The result as a subscriber that joins after it was published gets it.
std::optional<structloc_msgs::msg::CalibrationResult> LatchedResult() {
  dds_common::Node late(testing::TestNodeOptions("late_subscriber", kDomain));
  std::mutex mutex;
  std::optional<structloc_msgs::msg::CalibrationResult> result;
  const auto result_subscription = late.Subscribe<structloc_msgs::msg::CalibrationResultPubSubType>(
      dds_common::topics::kCalibration, [&](const structloc_msgs::msg::CalibrationResult& r) {
        std::lock_guard<std::mutex> lock(mutex);
        result = r;
      });
  testing::WaitUntil(
      [&] {
        std::lock_guard<std::mutex> lock(mutex);
        return result.has_value();
      },
      30s);
  std::lock_guard<std::mutex> lock(mutex);
  return result;
}

TEST(CalibrationComponent, LiveRecordingGivesALatchedResultWithinTheBars) {
  const auto truth =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/calibration_loop.xml"))
          .TrueParameters();
  const testing::TempDir dir;
  const std::string out = dir / "calibration";
  std::optional<structloc_msgs::msg::CalibrationResult> latched;
  const auto run =
      RunLive("maps/scenarios/calibration_loop.xml", {"--record-s", "90", "--out-dir", out},
              Calibrated, [&] { latched = LatchedResult(); });
  ASSERT_TRUE(run.finished) << run.output;
  ASSERT_TRUE(latched.has_value()) << "a late subscriber got no result\n" << run.output;
  const auto& result = *latched;
  ASSERT_TRUE(result.success()) << run.output;
  const auto& v = result.parameters();
  const auto& s = result.standard_deviations();
  std::printf(
      "live: radius %.6f +- %.1e (true %.6f), axle %.5f +- %.1e (true %.5f), offset %.5f +- %.1e "
      "(true %.5f)\n",
      v.wheel_radius_m(), s.wheel_radius_m(), truth.wheel_radius, v.axle_distance_m(),
      s.axle_distance_m(), truth.axle_distance, v.steering_offset_rad(), s.steering_offset_rad(),
      truth.steering_offset);
  EXPECT_LT(std::abs(v.wheel_radius_m() - truth.wheel_radius) / truth.wheel_radius, 0.001);
  EXPECT_LT(std::abs(v.axle_distance_m() - truth.axle_distance) / truth.axle_distance, 0.005);
  EXPECT_LT(std::abs(v.steering_offset_rad() - truth.steering_offset) * 180 / geometry::kPi, 0.05);
  EXPECT_EQ(result.estimated().size(), 3u);
  EXPECT_EQ(result.covariance().size(), 9u);
  EXPECT_NEAR(result.covariance()[0], s.wheel_radius_m() * s.wheel_radius_m(),
              1e-6 * s.wheel_radius_m() * s.wheel_radius_m());
  EXPECT_TRUE(std::filesystem::exists(out + "/calibrated.xml"));
  EXPECT_TRUE(std::filesystem::exists(out + "/encoders.csv"));

  // Restarted alone (every process of the run is gone), the component
  // publishes its last result again: a subscriber that joins now gets it.
  process::ChildProcess restarted(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_calibration",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--out-dir", out});
  const auto again = LatchedResult();
  ASSERT_TRUE(again.has_value()) << "no result after a restart\n" << restarted.CapturedOutput();
  EXPECT_TRUE(*again == result) << "the restarted component published another result";
  EXPECT_NE(restarted.CapturedOutput().find("published the last result again"), std::string::npos)
      << restarted.CapturedOutput();
}

TEST(CalibrationComponent, DifferentialDriveIsCalibratedLive) {
  const auto truth = simulation_core::LoadScenario(
                         testing::SourcePath("maps/scenarios/calibration_loop_differential.xml"))
                         .TrueParameters();
  const auto run =
      RunLive("maps/scenarios/calibration_loop_differential.xml",
              {"--record-s", "80", "--robot", testing::SourcePath("maps/robots/differential.xml")},
              [](const LiveRun& r) { return Calibrated(r) && !r.results.empty(); });
  ASSERT_TRUE(run.finished) << run.output;
  const auto& result = run.results.front();
  ASSERT_TRUE(result.success()) << run.output;
  const auto& v = result.parameters();
  std::printf(
      "live differential: left %.6f (true %.6f), right %.6f (true %.6f), separation %.5f "
      "(true %.5f)\n",
      v.left_wheel_radius_m(), truth.left_wheel_radius, v.right_wheel_radius_m(),
      truth.right_wheel_radius, v.wheel_separation_m(), truth.wheel_separation);
  EXPECT_TRUE(v.differential());
  EXPECT_LT(std::abs(v.left_wheel_radius_m() / truth.left_wheel_radius - 1), 0.001);
  EXPECT_LT(std::abs(v.right_wheel_radius_m() / truth.right_wheel_radius - 1), 0.001);
  EXPECT_LT(std::abs(v.wheel_separation_m() / truth.wheel_separation - 1), 0.005);
  EXPECT_EQ(result.estimated().size(), 3u);
}

TEST(CalibrationComponent, OnlineModePublishesEveryWindowWithItsCovariance) {
  const auto run =
      RunLive("maps/scenarios/calibration_loop.xml", {"--window-s", "40", "--every-s", "15"},
              [](const LiveRun& r) { return r.results.size() >= 3; });
  ASSERT_TRUE(run.finished) << run.output;
  double previous_end = -1.0;
  for (const auto& r : run.results) {
    ASSERT_TRUE(r.success()) << run.output;
    const double start = r.window_start().sec() + 1e-9 * r.window_start().nanosec();
    const double end = r.window_end().sec() + 1e-9 * r.window_end().nanosec();
    std::printf("online: window %.1f-%.1f s, radius %.6f +- %.1e, %zu changed\n", start, end,
                r.parameters().wheel_radius_m(), r.standard_deviations().wheel_radius_m(),
                r.changed().size());
    EXPECT_NEAR(end - start, 40.0, 0.5);
    EXPECT_GE(end - previous_end, 15.0 - 0.5);
    previous_end = end;
    EXPECT_EQ(r.estimated().size(), 3u);
    EXPECT_EQ(r.covariance().size(), 9u);
  }
}

}  // namespace
}  // namespace structloc
