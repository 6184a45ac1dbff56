// Tests on the real recordings in ../shared/data (ctest label shared_data,
// which CI runs; they fail, never skip, when the data is missing): the replay
// reads the real CARMEN logs without error (their quirks: 361-beam FLASER,
// ~81 m max-range values, non-monotonic stamps, GMapping's NEFF lines) in
// --no-map mode since there is no world model for them, and calibration cuts
// the real tricycle's dead-reckoning error against its tracker.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/replay/replay.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr const char* kMissing =
    "shared/ is not beside the checkout (run `ctest -LE shared_data` without it): ";

std::string SharedData(const std::string& name) {
  return std::string(STRUCTLOC_SOURCE_DIR) + "/../shared/data/" + name;
}

class RealLog : public ::testing::TestWithParam<const char*> {};

TEST_P(RealLog, ReplaysWithoutErrorInNoMapMode) {
  const std::string path = SharedData(GetParam());
  ASSERT_TRUE(std::filesystem::exists(path)) << kMissing << path;
  const testing::TempDir temp;
  replay::ReplayOptions o;
  o.no_map = true;
  o.log_path = path;
  o.initial_pose = geometry::Pose2D{};
  o.out_tum = temp / "real_log.tum";
  const auto report = replay::RunReplay(o);
  EXPECT_EQ(report.log.malformed, 0u);
  EXPECT_GT(report.log.scans, 500u);
  EXPECT_GT(report.scans_used, report.log.scans * 99 / 100);
  size_t rejected = 0;
  for (const auto& [why, n] : report.scans_rejected) rejected += n;
  EXPECT_EQ(report.scans_used + rejected, report.log.scans);
  std::ifstream tum(o.out_tum);
  size_t lines = 0;
  for (std::string line; std::getline(tum, line);) lines += !line.empty() && line[0] != '#';
  EXPECT_EQ(lines, report.scans_used);
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealLog,
                         ::testing::Values("mit-csail.clf.gz", "freiburg-079-corrected.log.gz",
                                           "intel-corrected.log.gz"),
                         [](const auto& info) {
                           std::string name = info.param;
                           return name.substr(0, name.find('-'));
                         });

TEST(RealData, TricycleDatasetImprovesDeadReckoningAgainstTheTracker) {
  const std::string data = SharedData("tricycle-calibration-dataset.txt");
  ASSERT_TRUE(std::filesystem::exists(data)) << kMissing << data;
  const testing::TempDir temp;
  const std::string dir = temp / "tricycle";
  process::ChildProcess convert(
      "/bin/bash",
      {testing::SourcePath("components/calibration_core/convert_tricycle_dataset.sh"), data, dir});
  ASSERT_EQ(convert.WaitExit(30s), 0) << convert.CapturedOutput();
  const auto nominal = kinematics::LoadRobotParameters(dir + "/nominal.xml");
  const auto encoders = calibration_core::ReadEncodersCsv(dir + "/encoders.csv");
  const auto fixes = calibration_core::ReadFixesCsv(dir + "/fixes.csv");
  calibration_core::CalibrationOptions o;
  for (int k = 0; k < calibration_core::kParameterCount; ++k) {  // steering gain and mounting too
    o.estimate[static_cast<size_t>(k)] =
        calibration_core::AppliesTo(static_cast<calibration_core::Parameter>(k), nominal.kind);
  }
  const auto r = calibration_core::Calibrate(encoders, fixes.fixes, nominal, o);
  ASSERT_TRUE(r.success);
  const double before = calibration_core::DeadReckoningRms(encoders, fixes.fixes, nominal);
  const double after = calibration_core::DeadReckoningRms(encoders, fixes.fixes, r.parameters);
  std::printf(
      "real tricycle: sensor dead-reckoning RMS vs tracker %.2f m nominal -> %.3f m calibrated "
      "(%.0fx); residual RMS %.2f -> %.2f\n",
      before, after, before / after, r.residual_rms_before, r.residual_rms_after);
  EXPECT_GT(before / after, 20.0);  // measured ~50x
  EXPECT_LT(r.residual_rms_after, r.residual_rms_before / 3);
}

}  // namespace
}  // namespace structloc
