// MatchScan (scan_matcher.hpp): a scan of a room taken 0.3 m and 8 deg from
// where the guess puts it is matched back to within millimetres, the match
// explains all of it and pins every direction; in a corridor the match says
// that it pins nothing along the corridor (a covariance that is large there),
// and, held there, keeps the guess's position along it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "structloc/slam_core/scan_matcher.hpp"

namespace structloc::slam_core {
namespace {

// Points every 2 cm along the walls of an axis-aligned box, seen from `pose`
// (in its frame), with range noise.
std::vector<Eigen::Vector2d> Box(double x0, double y0, double x1, double y1,
                                 const geometry::Pose2D& pose, std::mt19937& rng,
                                 bool ends = true) {
  std::normal_distribution<double> noise(0.0, 0.005);
  std::vector<Eigen::Vector2d> world;
  for (double x = x0; x <= x1; x += 0.02) {
    world.emplace_back(x, y0);
    world.emplace_back(x, y1);
  }
  if (ends) {
    for (double y = y0; y <= y1; y += 0.02) {
      world.emplace_back(x0, y);
      world.emplace_back(x1, y);
    }
  }
  std::vector<Eigen::Vector2d> seen;
  for (const auto& w : world) {
    const Eigen::Vector2d p = pose.ApplyInverse(w);
    seen.push_back(p + noise(rng) * p.normalized());
  }
  return seen;
}

TEST(ScanMatcher, ARoomScanIsMatchedBackFromAGuessOff) {
  std::mt19937 rng(1);
  const geometry::Pose2D truth{0.4, -0.2, 0.15};
  const ReferencePoints reference(Box(-3, -2, 4, 3, {}, rng), {});
  const auto scan = Box(-3, -2, 4, 3, truth, rng);
  const geometry::Pose2D guess{truth.x + 0.3, truth.y - 0.1, truth.theta + 0.14};
  const auto match = MatchScan(reference, scan, guess);
  EXPECT_NEAR(match.pose.x, truth.x, 0.005);
  EXPECT_NEAR(match.pose.y, truth.y, 0.005);
  EXPECT_NEAR(match.pose.theta, truth.theta, 0.002);
  EXPECT_GT(match.inlier_share, 0.95);
  EXPECT_LT(match.rms_m, 0.01);
  EXPECT_TRUE(match.constrained);
  EXPECT_LE(match.covariance(0, 0), 0.01 * 0.01 + 1e-12);
}

TEST(ScanMatcher, AlongACorridorTheMatchPinsNothing) {
  std::mt19937 rng(2);
  const ReferencePoints reference(Box(-10, -1, 10, 1, {}, rng, false), {});
  const auto scan = Box(-10, -1, 10, 1, {0.0, 0.05, 0.01}, rng, false);
  const auto match = MatchScan(reference, scan, {});
  EXPECT_FALSE(match.constrained);
  EXPECT_NEAR(match.pose.y, 0.05, 0.005) << "across the corridor it is pinned";
  EXPECT_GT(match.covariance(0, 0), 1000 * match.covariance(1, 1)) << "along it, not";
  EXPECT_LE(match.covariance(1, 1), 0.01 * 0.01 + 1e-12);
}

TEST(ScanMatcher, AlongACorridorAHeldMatchKeepsTheGuessAlongIt) {
  std::mt19937 rng(3);
  // A corridor with a door jamb too short to pin the position along it.
  const auto corridor = [&](const geometry::Pose2D& pose) {
    auto points = Box(-10, -1, 10, 1, pose, rng, false);
    for (double y = 1.0; y >= 0.5; y -= 0.02) points.push_back(pose.ApplyInverse({3.0, y}));
    return points;
  };
  const ReferencePoints reference(corridor({}), {});
  const geometry::Pose2D truth{0.0, 0.05, 0.01};
  const auto scan = corridor(truth);
  const geometry::Pose2D guess{0.4, 0.0, 0.0};
  ScanMatchOptions held;
  held.hold_unpinned = true;
  const auto match = MatchScan(reference, scan, guess, held);
  EXPECT_FALSE(match.constrained);
  EXPECT_NEAR(match.pose.x, guess.x, 0.005) << "held along the corridor";
  EXPECT_NEAR(match.pose.y, truth.y, 0.005);
  EXPECT_NEAR(match.pose.theta, truth.theta, 0.001);
  EXPECT_LT(MatchScan(reference, scan, guess).pose.x, 0.2)
      << "not held, the jamb alone pulls the match along the corridor";
}

// Of two reference points equally near, the one a search through cells of
// normal_radius_m (x, then y, then the points of a cell in order, the last of
// equals kept) ended with is the one given, so that matches are those that
// search gave: along a wall of points every 1/16 m, a query midway between two
// gets the later one, within one cell and across a cell's edge alike.
TEST(ScanMatcher, OfPointsEquallyNearTheReferenceGivesTheOneTheCellSearchGave) {
  std::vector<Eigen::Vector2d> wall;
  for (int k = 0; k < 64; ++k) wall.emplace_back(k / 16.0, 0.0);
  const ReferencePoints reference(wall, ScanMatchOptions{});
  for (int k = 0; k + 1 < 64; ++k) {
    for (const double y : {0.0, 0.125, -0.0625}) {
      const Eigen::Vector2d midway((k + 0.5) / 16.0, y);
      EXPECT_EQ(reference.Nearest(midway, 0.2), k + 1)
          << "between points " << k << " and " << k + 1;
    }
  }
}

}  // namespace
}  // namespace structloc::slam_core
