// Slam's partial matches (SlamOptions::partial_matches): a robot drives 15 m
// down a corridor whose walls pin no position along it, its odometry turning
// 0.5 deg per metre too far. Without partial matches every keyframe step is
// odometry's and the path bends with its drift (7.5 deg, a metre sideways);
// with them the walls hold the heading and the path keeps near the
// corridor's axis, odometry still giving the distance along it. The wall
// refinement is off, so that the steps alone are compared.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "structloc/slam_core/slam.hpp"

namespace structloc::slam_core {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDriftRadPerM = 0.5 * kPi / 180;

// Both walls (y = -1.5 and 1.5 m) within 4 m along them of a laser at
// `pose`, in its frame, with 5 mm range noise.
std::vector<Eigen::Vector2d> CorridorScan(const geometry::Pose2D& pose, std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, 0.005);
  std::vector<Eigen::Vector2d> points;
  for (double s = -4.0; s <= 4.0; s += 0.05) {
    for (double wall : {-1.5, 1.5})
      points.push_back(pose.ApplyInverse({pose.x + s, wall + noise(random)}));
  }
  return points;
}

struct Drive {
  std::vector<log_formats::StampedPose> path;
  SlamStats stats;
};

Drive DriveDownTheCorridor(bool partial_matches) {
  std::mt19937 random(37);
  SlamOptions options;
  options.partial_matches = partial_matches;
  options.walls.enabled = false;
  Slam slam(options);
  geometry::Pose2D odometry;
  for (int i = 0; i <= 150; ++i) {
    const geometry::Pose2D truth{0.1 * i, 0.0, 0.0};
    if (i > 0) odometry = geometry::Compose(odometry, {0.1, 0.0, 0.1 * kDriftRadPerM});
    slam.Add({0.2 * i, odometry, CorridorScan(truth, random)});
  }
  slam.Finish();
  return {slam.Trajectory(), slam.Stats()};
}

TEST(SlamPartialMatches, AlongACorridorTheWallsHoldTheHeadingOdometryDrifts) {
  const Drive dropped = DriveDownTheCorridor(false);
  EXPECT_EQ(dropped.stats.partial_matches, 0u);
  const auto& bent = dropped.path.back().pose;
  EXPECT_NEAR(bent.theta, 15 * kDriftRadPerM, 0.1 * kPi / 180) << "odometry's drift, whole";
  EXPECT_GT(bent.y, 0.5);

  const Drive held = DriveDownTheCorridor(true);
  EXPECT_EQ(held.stats.partial_matches + 1, held.stats.keyframes) << "every step";
  EXPECT_EQ(held.stats.odometry_edges, 0u);
  // Odometry's step still enters beside the match and its heading weighs in
  // a little (its information against the match's, about one part in seven).
  for (size_t i = 0; i < held.path.size(); ++i) {
    const auto& p = held.path[i].pose;
    EXPECT_LT(std::abs(p.theta), 0.2 * bent.theta) << "scan " << i;
    EXPECT_LT(std::abs(p.y), 0.2 * bent.y) << "scan " << i;
    EXPECT_NEAR(p.x, 0.1 * static_cast<double>(i), 0.02) << "scan " << i << ": odometry's distance";
  }
}

}  // namespace
}  // namespace structloc::slam_core
