// Odometry calibration: on simulator recordings with known errors (radius
// +1 %, axle -2 %, steering offset 0.5 deg) and fixes from the localisation,
// the estimate recovers the parameters within the bars with honest standard
// deviations over several seeds, and the odometry-only drift drops at least
// 10-fold; a straight-line-only recording says the axle distance is not
// observable; bad input files give clear errors. (The real tricycle dataset
// is calibrated in real_data_test.cpp.)
#include <gtest/gtest.h>

#include "test_paths.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc/log_formats/tum_reader.hpp"
#include "structloc/replay/replay.hpp"
#include "structloc/simulation_core/recorder.hpp"
#include "temp_dir.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
// Simulate, localise offline (fixes with covariances), return the folder.
std::string Record(simulation_core::Scenario scenario, const testing::TempDir& temp,
                   const std::string& tag) {
  const std::string dir = temp / tag;
  simulation_core::RecordScenario(scenario, dir);
  std::ifstream initial(dir + "/initial_pose");
  geometry::Pose2D p;
  initial >> p.x >> p.y >> p.theta;
  replay::ReplayOptions o;
  o.map_path = testing::SourcePath("maps/office_floor.xml");
  o.log_path = dir + "/run.clf";
  o.params_path = testing::SourcePath("maps/params/office_sick.xml");
  o.out_tum = dir + "/estimate.tum";
  o.fixes_path = dir + "/fixes.csv";
  o.initial_pose = p;
  replay::RunReplay(o);
  return dir;
}

TEST(Calibration, RecoversKnownErrorsWithHonestDeviationsOverSeeds) {
  auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/calibration_loop.xml"));
  const auto truth = scenario.TrueParameters();
  for (uint32_t seed : {21u, 22u, 23u}) {
    scenario.seed = seed;
    const testing::TempDir temp;
    const std::string dir = Record(scenario, temp, std::to_string(seed));
    const auto encoders = calibration_core::ReadEncodersCsv(dir + "/encoders.csv");
    const auto fixes = calibration_core::ReadFixesCsv(dir + "/fixes.csv");
    const auto r = calibration_core::Calibrate(encoders, fixes.fixes, scenario.nominal, {});
    ASSERT_TRUE(r.success);
    const double e_radius = r.parameters.wheel_radius - truth.wheel_radius;
    const double e_axle = r.parameters.axle_distance - truth.axle_distance;
    const double e_offset = r.parameters.steering_offset - truth.steering_offset;
    std::printf(
        "seed %u: radius %+.4f %% (%.1f sigma), axle %+.4f %% (%.1f sigma), offset %+.4f deg "
        "(%.1f sigma)\n",
        seed, 100 * e_radius / truth.wheel_radius, e_radius / r.standard_deviation[0],
        100 * e_axle / truth.axle_distance, e_axle / r.standard_deviation[1],
        e_offset * 180 / geometry::kPi, e_offset / r.standard_deviation[2]);
    EXPECT_LT(std::abs(e_radius) / truth.wheel_radius, 0.001);
    EXPECT_LT(std::abs(e_axle) / truth.axle_distance, 0.005);
    EXPECT_LT(std::abs(e_offset) * 180 / geometry::kPi, 0.05);
    EXPECT_LT(std::abs(e_radius), 3 * r.standard_deviation[calibration_core::kWheelRadius]);
    EXPECT_LT(std::abs(e_axle), 3 * r.standard_deviation[calibration_core::kAxleDistance]);
    EXPECT_LT(std::abs(e_offset), 3 * r.standard_deviation[calibration_core::kSteeringOffset]);
    // Odometry-only drift over the (closed) trajectory against the ground truth.
    std::vector<calibration_core::Fix> truth_fixes;
    for (const auto& p : log_formats::ReadTum(dir + "/truth.tum"))
      truth_fixes.push_back({p.stamp, p.pose});
    const double before =
        calibration_core::DeadReckoningRms(encoders, truth_fixes, scenario.nominal);
    const double after = calibration_core::DeadReckoningRms(encoders, truth_fixes, r.parameters);
    std::printf("  odometry-only drift RMS: %.3f m nominal, %.3f m calibrated (%.0fx)\n", before,
                after, before / after);
    EXPECT_GT(before / after, 10.0);
  }
}

TEST(Calibration, AStraightLineOnlySaysTheAxleDistanceIsNotObservable) {
  auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/calibration_loop.xml"));
  scenario.initial_pose = {17.0, 6.5, geometry::kPi};
  scenario.path.waypoints = {{4.0, 6.5}};
  scenario.duration_s = 25.0;
  const testing::TempDir temp;
  const std::string dir = Record(scenario, temp, "straight");
  const auto encoders = calibration_core::ReadEncodersCsv(dir + "/encoders.csv");
  const auto fixes = calibration_core::ReadFixesCsv(dir + "/fixes.csv");
  const auto r = calibration_core::Calibrate(encoders, fixes.fixes, scenario.nominal, {});
  EXPECT_FALSE(r.estimated[calibration_core::kAxleDistance]);
  EXPECT_DOUBLE_EQ(r.parameters.axle_distance, scenario.nominal.axle_distance);
  bool warned = false;
  for (const auto& w : r.warnings)
    warned = warned || w.find("axle_distance is not observable") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_TRUE(r.estimated[calibration_core::kWheelRadius]);
}

TEST(Calibration, BadInputFilesGiveClearErrors) {
  const testing::TempDir temp;
  auto Write = [&temp](const std::string& name, const std::string& text) {
    return temp.Write(name, text);
  };
  auto expect_error = [](auto&& read, const std::string& path, const std::string& problem) {
    try {
      read(path);
      ADD_FAILURE() << "accepted " << path;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
    }
  };
  auto enc = [](const std::string& p) { return calibration_core::ReadEncodersCsv(p); };
  auto fix = [](const std::string& p) { return calibration_core::ReadFixesCsv(p); };
  expect_error(enc, Write("empty.csv", ""), "empty file");
  expect_error(enc, Write("header.csv", "time,a,b\n1,2,3\n"), ":1: header must be");
  expect_error(enc,
               Write("unsorted.csv", "t,traction_ticks,steering_ticks\n1,0,0\n2,5,0\n1.5,9,0\n"),
               ":4: time 1.5 is not after");
  expect_error(enc, Write("text.csv", "t,traction_ticks,steering_ticks\n1,0,0\n2,x,0\n"),
               ":3: 'x' is not");
  expect_error(fix, Write("fewfix.csv", "t,x,y,theta\n1,0,0,0\n"), "fewer than three usable fixes");
  // A fix with NaN is dropped and counted, not fatal.
  const auto path = Write("nanfix.csv", "t,x,y,theta\n1,0,0,0\n2,nan,0,0\n3,1,0,0\n4,2,0,0\n");
  const auto f = calibration_core::ReadFixesCsv(path);
  EXPECT_EQ(f.dropped_non_finite, 1u);
  EXPECT_EQ(f.fixes.size(), 3u);
  // Counter wrap-around: tick deltas across the 32-bit wrap are positive.
  kinematics::RobotParameters p;
  EXPECT_EQ(p.TickDelta(4294967000u, 200u), 496);
}

}  // namespace
}  // namespace structloc
