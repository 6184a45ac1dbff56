// The live calibration over DDS: simulator (known parameter errors),
// localisation (fixes on rt/pose with covariances) and calibration as
// separate processes. After recording, the result is published RELIABLE +
// TRANSIENT_LOCAL: a subscriber that joins afterwards still receives it, and
// its values meet the accuracy bars.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <mutex>

#include "dds_test_support.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "structloc/process/child_process.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "structloc_msgs/msg/CalibrationResultPubSubTypes.h"
#include "temp_dir.hpp"
#include "test_domains.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = testing::domains::kCalibrationComponent;

TEST(CalibrationComponent, LiveRecordingGivesALatchedResultWithinTheBars) {
  const auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/calibration_loop.xml"));
  const auto truth = scenario.TrueParameters();
  const testing::TempDir dir;
  const std::string out = dir / "calibration";
  dds_common::Node observer(testing::TestNodeOptions("cal_observer", kDomain));
  std::mutex mutex;
  std::string calibration_state;
  const auto diagnostics_subscription =
      observer.Subscribe<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
          dds_common::topics::kDiagnostics, [&](const diagnostic_msgs::msg::DiagnosticArray& a) {
            std::lock_guard<std::mutex> lock(mutex);
            for (const auto& s : a.status()) {
              if (s.name() == "structloc/calibration") calibration_state = s.message();
            }
          });
  const std::vector<std::string> common = {"--domain", std::to_string(kDomain), "--qos",
                                           testing::ShippedQos()};
  auto args = [&](std::vector<std::string> extra) {
    extra.insert(extra.begin(), common.begin(), common.end());
    return extra;
  };
  const std::string bin = STRUCTLOC_BIN_DIR;
  const auto& p = scenario.initial_pose;
  process::ChildProcess calibration(bin + "/structloc_calibration",
                                    args({"--record-s", "90", "--out-dir", out}));
  process::ChildProcess localisation(
      bin + "/structloc_localisation",
      args({"--initial-pose",
            std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.theta)}));
  process::ChildProcess simulator(
      bin + "/structloc_simulator",
      args({"--scenario", testing::SourcePath("maps/scenarios/calibration_loop.xml"),
            "--time-scale", "8", "--wait-for-subscribers", "1", "--exit-when-done"}));
  ASSERT_TRUE(testing::WaitUntil(
      [&] {
        std::lock_guard<std::mutex> lock(mutex);
        return calibration_state.rfind("calibrat", 0) == 0 && calibration_state != "calibrating";
      },
      60s))
      << calibration.CapturedOutput();
  // A subscriber that joins only now.
  dds_common::Node late(testing::TestNodeOptions("late_subscriber", kDomain));
  std::optional<structloc_msgs::msg::CalibrationResult> result;
  const auto result_subscription = late.Subscribe<structloc_msgs::msg::CalibrationResultPubSubType>(
      dds_common::topics::kCalibration, [&](const structloc_msgs::msg::CalibrationResult& r) {
        std::lock_guard<std::mutex> lock(mutex);
        result = r;
      });
  ASSERT_TRUE(testing::WaitUntil(
      [&] {
        std::lock_guard<std::mutex> lock(mutex);
        return result.has_value();
      },
      30s))
      << calibration.CapturedOutput();
  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_TRUE(result->success()) << calibration.CapturedOutput();
  const auto& v = result->parameters();
  const auto& s = result->standard_deviations();
  std::printf(
      "live: radius %.6f +- %.1e (true %.6f), axle %.5f +- %.1e (true %.5f), offset %.5f +- %.1e "
      "(true %.5f)\n",
      v.wheel_radius_m(), s.wheel_radius_m(), truth.wheel_radius, v.axle_distance_m(),
      s.axle_distance_m(), truth.axle_distance, v.steering_offset_rad(), s.steering_offset_rad(),
      truth.steering_offset);
  EXPECT_LT(std::abs(v.wheel_radius_m() - truth.wheel_radius) / truth.wheel_radius, 0.001);
  EXPECT_LT(std::abs(v.axle_distance_m() - truth.axle_distance) / truth.axle_distance, 0.005);
  EXPECT_LT(std::abs(v.steering_offset_rad() - truth.steering_offset) * 180 / geometry::kPi, 0.05);
  EXPECT_TRUE(std::filesystem::exists(out + "/calibrated.xml"));
  EXPECT_TRUE(std::filesystem::exists(out + "/encoders.csv"));
}

}  // namespace
}  // namespace structloc
