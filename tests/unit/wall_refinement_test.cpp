// RefineWithWalls (wall_refinement.hpp): a robot drives 15 m down a corridor
// whose steps, as matched, each turn 0.2 deg too far, with no loop to close.
// The pose graph alone leaves the path bent metres off the corridor; the two
// straight walls every keyframe sees pull each pose back onto the corridor's
// axis and its heading along it. A scan's segments are found as the map
// builder finds them; without walls the poses stay where the graph put them;
// segments that do not match the poses are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "structloc/slam_core/pose_graph.hpp"
#include "structloc/slam_core/wall_refinement.hpp"

namespace structloc::slam_core {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kHalfWidth = 1.5;  // the walls at y = -1.5 and 1.5 m

// What a laser at `pose` sees of both walls within 4 m along them, in beam
// order (right wall front to back would not be beam order: right wall from
// behind to ahead, then left wall from ahead to behind), in its own frame,
// with 5 mm range noise.
std::vector<Eigen::Vector2d> CorridorScan(const geometry::Pose2D& pose, std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, 0.005);
  std::vector<Eigen::Vector2d> points;
  const geometry::Pose2D to_laser = geometry::Inverse(pose);
  for (double s = -4.0; s <= 4.0; s += 0.05)
    points.push_back(to_laser.Apply({pose.x + s, -kHalfWidth + noise(random)}));
  for (double s = 4.0; s >= -4.0; s -= 0.05)
    points.push_back(to_laser.Apply({pose.x + s, kHalfWidth + noise(random)}));
  return points;
}

struct Corridor {
  std::vector<geometry::Pose2D> truth;
  std::vector<PoseGraphEdge> steps;
  std::vector<std::vector<KeyframeSegment>> segments;
  Corridor() {
    std::mt19937 random(41);
    for (int k = 0; k <= 50; ++k) {
      truth.push_back({0.3 * k, 0.0, 0.0});
      segments.push_back(FindKeyframeSegments(CorridorScan(truth.back(), random)));
    }
    for (size_t i = 0; i + 1 < truth.size(); ++i) {
      PoseGraphEdge e;
      e.from = static_cast<int>(i);
      e.to = static_cast<int>(i + 1);
      e.measured = geometry::Between(truth[i], truth[i + 1]);
      e.measured.theta += 0.2 * kPi / 180;
      e.information = Eigen::Vector3d(1e4, 1e4, 4e4).asDiagonal();  // 1 cm, 0.005 rad
      steps.push_back(e);
    }
  }
  std::vector<geometry::Pose2D> AsMatched() const {
    std::vector<geometry::Pose2D> poses{truth[0]};
    for (const auto& e : steps) poses.push_back(geometry::Compose(poses.back(), e.measured));
    return poses;
  }
};

TEST(WallRefinement, AScanAlongACorridorGivesOneSegmentPerWall) {
  std::mt19937 random(7);
  const auto segments = FindKeyframeSegments(CorridorScan({2.0, 0.0, 0.3}, random));
  ASSERT_EQ(segments.size(), 2u);
  for (const auto& s : segments) {
    EXPECT_NEAR((s.b - s.a).norm(), 8.0, 0.1);
    EXPECT_LT(s.rms_m, 0.01);
  }
}

TEST(WallRefinement, TheCorridorsWallsStraightenAPathBentByItsSteps) {
  const Corridor corridor;
  std::vector<geometry::Pose2D> poses = corridor.AsMatched();
  OptimisePoseGraph(poses, corridor.steps);
  EXPECT_GT(std::abs(poses.back().y), 1.0);  // bent: the steps alone hold nothing else

  const auto summary = RefineWithWalls(poses, corridor.segments, corridor.steps, {}, {});
  EXPECT_TRUE(summary.usable);
  EXPECT_EQ(summary.walls, 2u);
  EXPECT_EQ(summary.observations, 2 * corridor.truth.size());
  for (size_t k = 0; k < poses.size(); ++k) {
    EXPECT_NEAR(poses[k].y, 0.0, 0.02) << "keyframe " << k;
    EXPECT_NEAR(poses[k].theta, 0.0, 0.2 * kPi / 180) << "keyframe " << k;
  }
}

TEST(WallRefinement, WithoutWallsThePosesStayAtTheGraphsOptimum) {
  const Corridor corridor;
  std::vector<geometry::Pose2D> graph = corridor.AsMatched();
  OptimisePoseGraph(graph, corridor.steps);
  std::vector<geometry::Pose2D> refined = graph;
  const std::vector<std::vector<KeyframeSegment>> none(refined.size());
  const auto summary = RefineWithWalls(refined, none, corridor.steps, {}, {});
  EXPECT_TRUE(summary.usable);
  EXPECT_EQ(summary.walls, 0u);
  for (size_t k = 0; k < graph.size(); ++k) {
    EXPECT_NEAR(refined[k].x, graph[k].x, 1e-6);
    EXPECT_NEAR(refined[k].y, graph[k].y, 1e-6);
    EXPECT_NEAR(refined[k].theta, graph[k].theta, 1e-8);
  }
}

TEST(WallRefinement, SegmentsOfOtherKeyframesThanThePosesAreRefused) {
  const Corridor corridor;
  std::vector<geometry::Pose2D> poses = corridor.AsMatched();
  poses.pop_back();
  EXPECT_THROW(RefineWithWalls(poses, corridor.segments, corridor.steps, {}, {}),
               std::invalid_argument);
}

}  // namespace
}  // namespace structloc::slam_core
