// GlobalStart (global_start.hpp): a scan of the office hall, searched against
// the whole map, gives the robot's initial pose (laser pose turned into the
// robot's with the sensor mount) with the covariance asked for; a scan that
// sees nothing gives none.
#include <gtest/gtest.h>

#include <random>

#include "initial_pose_expectations.hpp"
#include "office_scene.hpp"
#include "structloc/localisation_core/global/global_start.hpp"

namespace structloc::localisation_core {
namespace {

TEST(GlobalStart, AHallScanGivesTheRobotsPose) {
  const testing::OfficeScene office(4.71238898038469);
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.0025, 0.0025, 0.0009).asDiagonal();
  const GlobalStart start(office.world, office.options.sensor_mount, covariance);
  std::mt19937 rng(2);
  const auto attempt = start.Try(testing::SessionScanOf(office.Scan(1081, rng), 12.5));
  ASSERT_EQ(attempt.result.decision, GlobalDecision::kFound) << attempt.result.reason;
  ASSERT_TRUE(attempt.found);
  testing::ExpectFoundAt(*attempt.found, 12.5, office.truth, covariance);
}

TEST(GlobalStart, AScanThatSeesNothingGivesNoPose) {
  const testing::OfficeScene office(4.71238898038469);
  const GlobalStart start(office.world, office.options.sensor_mount, Eigen::Matrix3d::Identity());
  SessionScan empty;
  empty.geometry.angle_min = -2.35;
  empty.geometry.angle_increment = 4.7 / 1080;
  empty.geometry.range_max = 30.0;
  empty.ranges.assign(1081, 30.0f);
  const auto attempt = start.Try(empty);
  EXPECT_EQ(attempt.result.decision, GlobalDecision::kNotFound);
  EXPECT_FALSE(attempt.found);
}

}  // namespace
}  // namespace structloc::localisation_core
