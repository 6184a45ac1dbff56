// PointTree (point_tree.hpp): the k-d tree gives the scan matcher the same
// nearest point a look at every point would, within the distance asked (a
// point at exactly that distance counted), the lowest index among points
// equally near (repeated points, points on a grid), and none when nothing
// is that near or there are no points at all.
#include <gtest/gtest.h>

#include <random>

#include "structloc/slam_core/point_tree.hpp"

namespace structloc::slam_core {
namespace {

// What the tree must answer: every point looked at.
int NearestByLookingAtAll(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& p,
                          double max_distance_m) {
  int best = -1;
  double best_d2 = max_distance_m * max_distance_m;
  for (size_t i = 0; i < points.size(); ++i) {
    const double d2 = (points[i] - p).squaredNorm();
    if (d2 < best_d2 || (d2 == best_d2 && best < 0)) {
      best_d2 = d2;
      best = static_cast<int>(i);
    }
  }
  return best;
}

TEST(PointTree, GivesTheNearestPointEveryPointWouldGive) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> place(-10.0, 10.0);
  std::vector<Eigen::Vector2d> points;
  // Walls (points along lines, as scans give) and scattered clutter.
  for (int k = 0; k < 3000; ++k) points.emplace_back(place(rng), 0.01 * k - 15.0);
  for (int k = 0; k < 2000; ++k) points.emplace_back(0.005 * k - 5.0, 3.0);
  for (int k = 0; k < 500; ++k) points.emplace_back(place(rng), place(rng));
  const PointTree tree(points);
  int found = 0;
  for (int q = 0; q < 20000; ++q) {
    const Eigen::Vector2d p(place(rng), place(rng));
    for (const double reach : {0.05, 0.2, 1.0}) {
      const int expected = NearestByLookingAtAll(points, p, reach);
      ASSERT_EQ(tree.Nearest(p, reach), expected)
          << "query " << p.transpose() << " reach " << reach;
      found += expected >= 0;
    }
  }
  EXPECT_GT(found, 10000);  // the queries did find points, not only misses
}

TEST(PointTree, OfPointsEquallyNearGivesTheLowestIndexAndCountsTheEdge) {
  std::vector<Eigen::Vector2d> points;
  for (int repeat = 0; repeat < 3; ++repeat) {
    for (int x = 0; x < 20; ++x) {
      for (int y = 0; y < 20; ++y) points.emplace_back(0.1 * x, 0.1 * y);
    }
  }
  const PointTree tree(points);
  for (int x = 0; x < 19; ++x) {
    for (int y = 0; y < 19; ++y) {
      // Midway between four grid points, each repeated three times.
      const Eigen::Vector2d p(0.1 * x + 0.05, 0.1 * y + 0.05);
      EXPECT_EQ(tree.Nearest(p, 1.0), NearestByLookingAtAll(points, p, 1.0));
    }
  }
  EXPECT_EQ(tree.Nearest({0.0, -0.5}, 0.5), 0);  // exactly at the distance asked
  EXPECT_EQ(tree.Nearest({0.0, -0.5}, 0.4999), -1);
}

TEST(PointTree, WithoutPointsNearFindsNone) {
  EXPECT_EQ(PointTree().Nearest({0.0, 0.0}, 100.0), -1);
  EXPECT_EQ(PointTree(std::vector<Eigen::Vector2d>{}).Nearest({0.0, 0.0}, 100.0), -1);
  const PointTree one(std::vector<Eigen::Vector2d>{{5.0, 5.0}});
  EXPECT_EQ(one.Nearest({0.0, 0.0}, 1.0), -1);
  EXPECT_EQ(one.Nearest({4.5, 5.0}, 1.0), 0);
}

}  // namespace
}  // namespace structloc::slam_core
