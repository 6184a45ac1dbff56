// SLAM on the raw MIT CSAIL log in ../shared/data (label shared_data), judged
// by Kuemmerle et al. 2009's relations. The metric first: raw odometry gives
// the figure the benchmark's users quote for it (1.68 +- 5.29 m, 5.1 +- 8.2
// deg), so the metric is theirs. Then structloc slam's path must beat raw
// odometry tenfold in translation and twofold in rotation: a regression
// guard, well short of the particle-filter class (0.05 m, 1 deg) the SLAM
// issue asks for, which is not met yet. Stopped by Ctrl-C part of the way,
// `structloc slam` writes the path and map of the scans it had.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>

#include "structloc/log_formats/relations_reader.hpp"
#include "structloc/log_formats/tum_reader.hpp"
#include "structloc/map_building/posed_scans.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/replay/relation_error.hpp"
#include "structloc/slam_core/slam.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"
#include "wait_until.hpp"

namespace structloc {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct Mit {
  map_building::PosedScanLog log =
      map_building::ReadPosedScans(testing::SourcePath("../shared/data/mit-csail.clf.gz"), {});
  std::vector<log_formats::Relation> relations =
      log_formats::ReadRelations(testing::SourcePath("../shared/data/mit-csail.relations"));
};

TEST(SlamOnRealLogs, TheRelationMetricGivesRawOdometryItsPublishedFigure) {
  const Mit mit;
  std::vector<log_formats::StampedPose> odometry;
  for (const auto& s : mit.log.scans) {
    ASSERT_TRUE(s.robot_pose);
    odometry.push_back({s.stamp, *s.robot_pose});
  }
  const auto e = replay::CompareRelations(odometry, mit.relations);
  EXPECT_EQ(e.missing, 0u);
  EXPECT_EQ(e.used, mit.relations.size());
  EXPECT_NEAR(e.translation_mean_m, 1.68, 0.005);
  EXPECT_NEAR(e.translation_std_m, 5.29, 0.005);
  EXPECT_NEAR(e.rotation_mean_rad / kDeg, 5.1, 0.05);
  EXPECT_NEAR(e.rotation_std_rad / kDeg, 8.2, 0.05);
}

TEST(SlamOnRealLogs, TheMitPathBeatsRawOdometryByFar) {
  const Mit mit;
  slam_core::Slam slam;
  std::vector<log_formats::StampedPose> odometry;
  for (const auto& s : mit.log.scans) {
    slam.Add({s.stamp, s.laser_pose, s.points});  // the laser sits on the robot's origin here
    odometry.push_back({s.stamp, *s.robot_pose});
  }
  slam.Finish();
  const auto path = slam.Trajectory();
  ASSERT_EQ(path.size(), mit.log.scans.size());
  const auto e = replay::CompareRelations(path, mit.relations);
  const auto raw = replay::CompareRelations(odometry, mit.relations);
  const auto& st = slam.Stats();
  std::printf(
      "MIT CSAIL: %zu keyframes, %zu loops closed; relations %.3f +- %.3f m, %.2f +- "
      "%.2f deg (raw odometry %.2f m, %.1f deg)\n",
      st.keyframes, st.loops_closed, e.translation_mean_m, e.translation_std_m,
      e.rotation_mean_rad / kDeg, e.rotation_std_rad / kDeg, raw.translation_mean_m,
      raw.rotation_mean_rad / kDeg);
  EXPECT_EQ(e.used, mit.relations.size());
  EXPECT_GT(st.loops_closed, 0u);
  EXPECT_LT(e.translation_mean_m, raw.translation_mean_m / 10.0);
  EXPECT_LT(e.rotation_mean_rad, raw.rotation_mean_rad / 2.0);
}

TEST(SlamOnRealLogs, CtrlCPartOfTheWayWritesThePathAndMapSoFar) {
  using namespace std::chrono_literals;
  const testing::TempDir temp;
  const std::string poses = temp / "path.tum", world = temp / "world.xml";
  process::ChildProcess slam(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc",
      {"slam", "--log", testing::SourcePath("../shared/data/mit-csail.clf.gz"), "--poses-out",
       poses, "--out", world});
  ASSERT_TRUE(testing::WaitUntil(
      [&] { return slam.CapturedOutput().find("1000 of 1988 scans") != std::string::npos; }, 120s))
      << slam.CapturedOutput();
  slam.Signal(SIGINT);
  ASSERT_EQ(slam.WaitExit(120s), 0) << slam.CapturedOutput();
  const std::string said = slam.CapturedOutput();
  EXPECT_NE(said.find("stopped (Ctrl-C)"), std::string::npos) << said;
  EXPECT_NE(said.find("map check of the built map"), std::string::npos) << said;
  const auto path = log_formats::ReadTum(poses);
  EXPECT_GE(path.size(), 1000u);
  EXPECT_LT(path.size(), 1988u);
  EXPECT_TRUE(std::filesystem::exists(world));
}

}  // namespace
}  // namespace structloc
