// Slam's threads (SlamOptions::threads): a robot drives three laps of a
// circle in a room with a cupboard, its odometry turning half a degree per
// metre too far, so that loops close on every lap. The keyframes' loop
// candidates and the scans between keyframes are matched on one thread or
// several; the path must be the same to the last bit, and the loops must have
// closed. It stands still first, so that scans wait for a keyframe longer
// than Slam holds them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "structloc/slam_core/slam.hpp"

namespace structloc::slam_core {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kStillScans = 150;

// Points every 5 cm along the walls of an 8 x 5 m room and a 1 x 0.6 m
// cupboard in it (no symmetry to confuse a match), in the frame of a laser at
// `pose`, with 5 mm noise; the room is convex and the cupboard small, so
// nothing is hidden that matters here.
std::vector<Eigen::Vector2d> RoomScan(const geometry::Pose2D& pose, std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, 0.005);
  std::vector<Eigen::Vector2d> points;
  const auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    const double length = (b - a).norm();
    const Eigen::Vector2d across = Eigen::Vector2d(a.y() - b.y(), b.x() - a.x()) / length;
    for (double s = 0.0; s <= length; s += 0.05)
      points.push_back(pose.ApplyInverse(a + (b - a) * (s / length) + across * noise(random)));
  };
  wall({-4, -2.5}, {4, -2.5});
  wall({4, -2.5}, {4, 2.5});
  wall({4, 2.5}, {-4, 2.5});
  wall({-4, 2.5}, {-4, -2.5});
  wall({2.0, 1.0}, {3.0, 1.0});
  wall({3.0, 1.0}, {3.0, 1.6});
  return points;
}

struct Laps {
  std::vector<log_formats::StampedPose> path;
  SlamStats stats;
};

Laps DriveLaps(int threads) {
  std::mt19937 random(41);
  SlamOptions options;
  options.threads = threads;
  Slam slam(options);
  geometry::Pose2D odometry, last_truth;
  const double radius = 1.5, step = 0.1;
  const int scans = static_cast<int>(3 * 2 * kPi * radius / step);
  // It stands still for the first kStillScans (no keyframe is added meanwhile).
  for (int i = 0; i <= kStillScans + scans; ++i) {
    const double a = std::max(0, i - kStillScans) * step / radius;
    const geometry::Pose2D truth{radius * std::sin(a), -radius * std::cos(a), a};
    if (i > 0) {
      geometry::Pose2D moved = geometry::Between(last_truth, truth);
      moved.theta += step * 0.5 * kPi / 180;
      odometry = geometry::Compose(odometry, moved);
    }
    last_truth = truth;
    slam.Add({0.2 * i, odometry, RoomScan(truth, random)});
  }
  slam.Finish();
  return {slam.Trajectory(), slam.Stats()};
}

TEST(SlamThreads, ThePathIsTheSameOnOneThreadOrSeveral) {
  const Laps one = DriveLaps(1);
  EXPECT_GT(one.stats.loops_closed, 10u);
  for (int i = 0; i <= kStillScans; ++i) {
    EXPECT_NEAR(one.path[i].pose.x, 0.0, 0.01) << "standing still, scan " << i;
    EXPECT_NEAR(one.path[i].pose.y, 0.0, 0.01) << "standing still, scan " << i;
  }
  for (const int threads : {2, 3}) {
    const Laps several = DriveLaps(threads);
    EXPECT_EQ(several.stats.loops_tried, one.stats.loops_tried);
    EXPECT_EQ(several.stats.loops_closed, one.stats.loops_closed);
    ASSERT_EQ(several.path.size(), one.path.size());
    for (size_t i = 0; i < one.path.size(); ++i) {
      EXPECT_EQ(several.path[i].pose.x, one.path[i].pose.x) << threads << " threads, scan " << i;
      EXPECT_EQ(several.path[i].pose.y, one.path[i].pose.y) << threads << " threads, scan " << i;
      EXPECT_EQ(several.path[i].pose.theta, one.path[i].pose.theta) << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace structloc::slam_core
