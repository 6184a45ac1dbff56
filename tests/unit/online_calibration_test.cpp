// Online calibration: a differential-drive robot drives the calibration loop
// twice, its right tyre changed (1 % larger) between the two rounds; the
// sliding-window estimate flags no change while nothing changed, flags the
// right wheel radius once a window after the change is compared with one
// before it, and then follows the new radius. The recording is one stream:
// the second round's encoder counters continue the first's, its stamps follow
// on and its fixes are moved rigidly to where the first round ended.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "simulated_calibration.hpp"
#include "structloc/calibration_core/calibration_problem.hpp"
#include "structloc/calibration_core/online_calibration.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

namespace cc = calibration_core;

simulation_core::Scenario DifferentialLoop() {
  auto scenario = simulation_core::LoadScenario(
      testing::SourcePath("maps/scenarios/calibration_loop_differential.xml"));
  scenario.laser.beams = 10;  // the calibration uses no scans
  return scenario;
}

// `second` appended to `first` as if driven right after it.
testing::SimulatedCalibration Append(testing::SimulatedCalibration first,
                                     const testing::SimulatedCalibration& second,
                                     const geometry::Pose2D& first_end,
                                     const geometry::Pose2D& second_start, int counter_bits) {
  const double dt = first.encoders.back().t - second.encoders.front().t + 0.01;
  const uint64_t mask = (uint64_t{1} << counter_bits) - 1;
  const uint64_t left = (first.encoders.back().left_ticks - second.encoders.front().left_ticks);
  const uint64_t right = (first.encoders.back().right_ticks - second.encoders.front().right_ticks);
  for (auto s : second.encoders) {
    s.t += dt;
    s.left_ticks = (s.left_ticks + left) & mask;
    s.right_ticks = (s.right_ticks + right) & mask;
    first.encoders.push_back(s);
  }
  const geometry::Pose2D move = geometry::Compose(first_end, geometry::Inverse(second_start));
  for (auto f : second.fixes) {
    f.t += dt;
    f.pose = geometry::Compose(move, f.pose);
    first.fixes.push_back(f);
  }
  return first;
}

TEST(OnlineCalibration, FlagsATyreChangeAndNothingElse) {
  const testing::TempDir temp;
  auto before = DifferentialLoop();
  auto after = before;
  after.errors.right_wheel_radius_scale *= 1.01;  // the new, larger right tyre
  const auto a = testing::RecordCalibration(before, 1, temp / "before");
  const auto b = testing::RecordCalibration(after, 2, temp / "after");
  const auto run =
      Append(a, b, a.true_poses.back(), b.true_poses.front(), before.nominal.traction_counter_bits);
  const double change_t = a.encoders.back().t;  // the path ends before the scenario's duration
  const double new_right = after.TrueParameters().right_wheel_radius;

  cc::OnlineCalibrationOptions online;
  online.window_s = 50.0;
  online.period_s = 10.0;
  cc::OnlineCalibration calibration(before.nominal, testing::SimulatorNoiseOptions(before), online);
  size_t fixes = 0, estimates = 0;
  bool flagged_right = false;
  double last_right = 0.0;
  for (const auto& e : run.encoders) {
    ASSERT_TRUE(calibration.AddEncoders(e));
    while (fixes < run.fixes.size() && run.fixes[fixes].t <= e.t) {
      ASSERT_TRUE(calibration.AddFix(run.fixes[fixes++]));
    }
    if (!calibration.Due()) continue;
    const auto estimate = calibration.Estimate();
    ++estimates;
    // A window across the change mixes two robots: it may fail or flag anything.
    const bool straddles = estimate.window_start_s < change_t && estimate.window_end_s > change_t;
    if (straddles) continue;
    ASSERT_TRUE(estimate.report.success) << estimate.report.failure;
    const auto values = cc::ValuesOf(estimate.report.parameters);
    std::printf("window %6.1f-%6.1f s: left %.6f right %.6f separation %.5f; %zu changed%s\n",
                estimate.window_start_s, estimate.window_end_s, values[cc::kLeftWheelRadius],
                values[cc::kRightWheelRadius], values[cc::kWheelSeparation],
                estimate.changes.size(),
                estimate.changes.empty() ? "" : (": " + Describe(estimate.changes[0])).c_str());
    EXPECT_LE(estimate.window_end_s - estimate.window_start_s, online.window_s + 1e-9);
    const bool same_robot =
        estimate.window_end_s <= change_t ||
        (estimate.reference_end_s && *estimate.reference_end_s - online.window_s >= change_t);
    if (same_robot) {
      EXPECT_TRUE(estimate.changes.empty()) << "a change flagged where nothing changed";
    }
    for (const auto& change : estimate.changes) {
      if (change.parameter == cc::kRightWheelRadius && change.to > change.from) {
        flagged_right = true;
      }
    }
    last_right = values[cc::kRightWheelRadius];
  }
  EXPECT_GE(estimates, 12u);
  EXPECT_TRUE(flagged_right) << "the new right tyre was never flagged";
  EXPECT_LT(std::abs(last_right / new_right - 1.0), 2e-4) << "the estimate did not follow it";
}

TEST(OnlineCalibration, RefusesBadOptionsAndOutOfOrderSamples) {
  const auto scenario = DifferentialLoop();
  cc::OnlineCalibrationOptions online;
  online.window_s = 0.0;
  EXPECT_THROW(
      cc::OnlineCalibration(scenario.nominal, testing::SimulatorNoiseOptions(scenario), online),
      std::invalid_argument);
  online = {};
  cc::OnlineCalibration calibration(scenario.nominal, testing::SimulatorNoiseOptions(scenario),
                                    online);
  EXPECT_TRUE(calibration.AddEncoders({1.0, 0, 0, 10, 10}));
  EXPECT_FALSE(calibration.AddEncoders({0.5, 0, 0, 10, 10}));
  EXPECT_FALSE(calibration.Due());
  EXPECT_EQ(calibration.Stats().encoders_out_of_order, 1u);
}

// The review's case: one wheel-encoder sample stamped far ahead made the
// next window end there, forgot everything before it, and counted every later
// sample out of order, so that no estimate came again until a restart.
TEST(OnlineCalibration, ASampleStampedFarAheadDoesNotStopTheEstimates) {
  const testing::TempDir temp;
  const auto scenario = DifferentialLoop();
  const auto run = testing::RecordCalibration(scenario, 1, temp / "run");
  cc::OnlineCalibrationOptions online;
  online.window_s = 40.0;
  online.period_s = 10.0;
  cc::OnlineCalibration calibration(scenario.nominal, testing::SimulatorNoiseOptions(scenario),
                                    online);
  size_t fix = 0, estimates = 0;
  bool planted = false;
  for (const auto& sample : run.encoders) {
    while (fix < run.fixes.size() && run.fixes[fix].t <= sample.t) {
      calibration.AddFix(run.fixes[fix++]);
    }
    calibration.AddEncoders(sample);
    if (!planted && sample.t > run.encoders.front().t + 10.0) {
      auto future = sample;
      future.t += 1e6;
      EXPECT_FALSE(calibration.AddEncoders(future));
      planted = true;
    }
    if (calibration.Due()) {
      const auto estimate = calibration.Estimate(calibration.NextWindow());
      estimates += estimate.report.success;
    }
  }
  ASSERT_TRUE(planted);
  const double span = run.encoders.back().t - run.encoders.front().t;
  ASSERT_GT(span, 2.0 * online.window_s) << "the run is too short to test this";
  EXPECT_GE(estimates, static_cast<size_t>((span - online.window_s) / online.period_s))
      << "of a " << span << " s run";
  EXPECT_EQ(calibration.Stats().encoders_out_of_order, 1u);
}

}  // namespace
}  // namespace structloc
