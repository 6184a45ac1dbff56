// PoseGraph (pose_graph.hpp): a square driven with odometry that turns 2 deg
// too much per corner ends far from its start; one loop closure puts every
// corner back within 15 cm. A wrong loop closure among right ones
// goes through the robust loss and does not bend the square; a bad edge is
// refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "structloc/slam_core/pose_graph.hpp"

namespace structloc::slam_core {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The true square, 10 m a side, 4 poses per side, and the odometry edges of
// a robot that turns `extra` rad too much at each corner.
struct Square {
  std::vector<geometry::Pose2D> truth;
  std::vector<PoseGraphEdge> odometry;
  explicit Square(double extra) {
    geometry::Pose2D p{0, 0, 0};
    for (int side = 0; side < 4; ++side) {
      for (int k = 0; k < 4; ++k) {
        truth.push_back(p);
        const bool corner = k == 3;
        const geometry::Pose2D step{2.5, 0.0, corner ? kPi / 2 : 0.0};
        p = geometry::Compose(p, step);
      }
    }
    for (size_t i = 0; i + 1 < truth.size(); ++i) {
      geometry::Pose2D measured = geometry::Between(truth[i], truth[i + 1]);
      if (std::abs(measured.theta) > 1.0) measured.theta += extra;
      PoseGraphEdge e;
      e.from = static_cast<int>(i);
      e.to = static_cast<int>(i + 1);
      e.measured = measured;
      e.information = Eigen::Vector3d(100, 100, 1000).asDiagonal();
      odometry.push_back(e);
    }
  }
  std::vector<geometry::Pose2D> DeadReckoned() const {
    std::vector<geometry::Pose2D> poses{truth[0]};
    for (const auto& e : odometry) poses.push_back(geometry::Compose(poses.back(), e.measured));
    return poses;
  }
  PoseGraphEdge Closure(int from, int to, const geometry::Pose2D& measured) const {
    PoseGraphEdge e;
    e.from = from;
    e.to = to;
    e.measured = measured;
    e.information = Eigen::Vector3d(1e4, 1e4, 1e5).asDiagonal();
    e.robust = true;
    return e;
  }
};

double WorstError(const std::vector<geometry::Pose2D>& a, const std::vector<geometry::Pose2D>& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::hypot(a[i].x - b[i].x, a[i].y - b[i].y));
  return worst;
}

TEST(PoseGraph, OneLoopClosurePutsADriftedSquareBack) {
  const Square square(2.0 * kPi / 180.0);
  auto poses = square.DeadReckoned();
  ASSERT_GT(WorstError(poses, square.truth), 0.5);
  auto edges = square.odometry;
  const int last = static_cast<int>(poses.size()) - 1;
  edges.push_back(square.Closure(0, last, geometry::Between(square.truth[0], square.truth[last])));
  const auto summary = OptimisePoseGraph(poses, edges);
  EXPECT_TRUE(summary.usable);
  EXPECT_LT(summary.final_cost, summary.initial_cost);
  // The closure is obeyed, and the drift spread along the square: what is
  // left is the compromise between odometry's edges, not the drift.
  const auto closure = geometry::Between(poses[0], poses[last]);
  const auto truth = geometry::Between(square.truth[0], square.truth[last]);
  EXPECT_NEAR(closure.x, truth.x, 0.01);
  EXPECT_NEAR(closure.y, truth.y, 0.01);
  EXPECT_LT(WorstError(poses, square.truth), 0.15);
  EXPECT_NEAR(poses[0].x, 0.0, 1e-12) << "the first pose holds the frame";
}

TEST(PoseGraph, AWrongLoopClosureDoesNotBendTheSquare) {
  const Square square(0.0);
  auto edges = square.odometry;
  const int last = static_cast<int>(square.truth.size()) - 1;
  for (int i = 0; i < 4; ++i)
    edges.push_back(square.Closure(i, last - 3 + i,
                                   geometry::Between(square.truth[i], square.truth[last - 3 + i])));
  // A look-alike place 3 m off, matched as tightly as the right ones.
  edges.push_back(square.Closure(
      2, 9,
      geometry::Compose(geometry::Between(square.truth[2], square.truth[9]), {3.0, 0.0, 0.0})));
  auto poses = square.DeadReckoned();
  OptimisePoseGraph(poses, edges);
  EXPECT_LT(WorstError(poses, square.truth), 0.1);
  // Without the robust loss the same edge bends it by far more.
  edges.back().robust = false;
  auto bent = square.DeadReckoned();
  OptimisePoseGraph(bent, edges);
  EXPECT_GT(WorstError(bent, square.truth), 0.5);
}

TEST(PoseGraph, AnEdgeToAPoseThatDoesNotExistIsRefusedByName) {
  std::vector<geometry::Pose2D> poses(3);
  PoseGraphEdge e;
  e.from = 1;
  e.to = 7;
  try {
    OptimisePoseGraph(poses, {e});
    FAIL() << "accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("poses 1 and 7 of 3"), std::string::npos)
        << error.what();
  }
  e.to = 2;
  e.information(0, 0) = NAN;
  EXPECT_THROW(OptimisePoseGraph(poses, {e}), std::invalid_argument);
}

}  // namespace
}  // namespace structloc::slam_core
