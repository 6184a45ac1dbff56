// Data association on real scans (issue 12): a window pairs with a wall line
// only where it overlaps one of the line's map walls (not across a doorway),
// a pairing inside the Mahalanobis gates of two walls is dropped, the map's
// own error joins every pairing's covariance, and point features pass a
// Mahalanobis gate under the prior.
#include <gtest/gtest.h>

#include "structloc/localisation_core/association/point_gate.hpp"
#include "structloc/localisation_core/features/walls/wall_clustering.hpp"

namespace structloc::localisation_core {
namespace {

// The wall line y = y0 seen from the origin (heading 0), made of map walls
// over x in each of `spans`.
void AddLine(ExpectedWalls& f, double y0, const std::vector<std::pair<double, double>>& spans) {
  ExpectedWall e;
  e.line_index = static_cast<int>(f.walls.size());
  e.model_id = e.line_index + 1;
  e.world = {y0, geometry::kHalfPi};
  e.world_c = 0.0;
  e.world_s = 1.0;
  e.r = y0;
  e.c = 0.0;
  e.s = 1.0;
  for (const auto& [x0, x1] : spans) {  // along-line coordinate t = -x
    f.extents.push_back({e.line_index, -x1, -x0, -0.5 * (x0 + x1), 0.5 * (x1 - x0)});
  }
  f.walls.push_back(e);
  f.IndexExtents();
}

WindowLine Window(double x, double y) {
  WindowLine w;
  w.valid = true;
  w.line.r = y;
  w.line.cos_alpha = 0.0;
  w.line.sin_alpha = 1.0;
  w.line.xm = x;
  w.line.ym = y;
  w.line.sse = 1e-6;
  w.line.degenerate = false;
  return w;
}

WallClusterOptions RealMapOptions() {
  WallClusterOptions o;
  o.extent_margin_m = 0.1;
  o.map_sigma_r_m = 0.02;
  o.map_sigma_alpha_rad = 0.026;
  o.gate_chi2 = 5.99;
  return o;
}

const Eigen::Matrix3d kPrior = Eigen::Vector3d(4e-4, 4e-4, 1e-4).asDiagonal();

TEST(PairingGates, AWindowInADoorwayPairsWithNoWall) {
  ExpectedWalls f;
  AddLine(f, 2.0, {{-3.0, -0.5}, {0.5, 3.0}});  // a 1 m doorway around x = 0
  const std::vector<WindowLine> windows = {Window(1.5, 2.0), Window(0.0, 2.0), Window(-2.0, 2.0)};
  std::vector<int> assignment;
  WallClusterWork work;
  AssignWindowsByExpectation(windows, f, {}, kPrior, RealMapOptions(), work, assignment);
  EXPECT_EQ(assignment, (std::vector<int>{0, -1, 0}));
}

TEST(PairingGates, AWindowFarFromItsWallUnderATightPriorPairsWithNothing) {
  ExpectedWalls f;
  AddLine(f, 2.0, {{-3.0, 3.0}});
  const std::vector<WindowLine> windows = {Window(1.0, 2.15)};  // 15 cm off; prior sigma 2 cm
  std::vector<int> assignment;
  WallClusterWork work;
  AssignWindowsByExpectation(windows, f, {}, kPrior, RealMapOptions(), work, assignment);
  EXPECT_EQ(assignment[0], -1);
  WallClusterOptions thesis = RealMapOptions();
  thesis.gate_chi2 = 0.0;  // the thesis' fixed 0.2 m gate alone takes it
  AssignWindowsByExpectation(windows, f, {}, kPrior, thesis, work, assignment);
  EXPECT_EQ(assignment[0], 0);
}

WallCluster ClusterAt(int expected, double y) {
  WallCluster c;
  c.expected_index = expected;
  c.refined_r = y;
  c.refined_alpha = geometry::kHalfPi;
  c.covariance = Eigen::Vector2d(1e-6, 1e-6).asDiagonal();
  c.centroid = {1.0, y};
  return c;
}

TEST(PairingGates, AClusterBetweenTwoParallelWallsIsAmbiguousAndDropped) {
  ExpectedWalls f;
  AddLine(f, 2.0, {{-3.0, 3.0}});
  AddLine(f, 2.04, {{-3.0, 3.0}});  // a second wall 4 cm behind, both within the gates
  std::vector<WallCluster> clusters = {ClusterAt(0, 2.02)};
  GateWallClusters(f, {}, kPrior, RealMapOptions(), clusters);
  EXPECT_TRUE(clusters.empty());
}

TEST(PairingGates, AClusterGainsTheMapsErrorWhenItPasses) {
  ExpectedWalls f;
  AddLine(f, 2.0, {{-3.0, 3.0}});
  std::vector<WallCluster> clusters = {ClusterAt(0, 2.01)};
  GateWallClusters(f, {}, kPrior, RealMapOptions(), clusters);
  ASSERT_EQ(clusters.size(), 1u);
  // 2 cm of offset at the wall's centre, which the sensor faces (no lever arm).
  EXPECT_NEAR(clusters[0].covariance(0, 0), 1e-6 + 4e-4, 1e-9);
  EXPECT_GT(clusters[0].covariance(1, 1), 1e-6);
  std::vector<WallCluster> far = {ClusterAt(0, 2.3)};
  GateWallClusters(f, {}, kPrior, RealMapOptions(), far);
  EXPECT_TRUE(far.empty());
}

TEST(PairingGates, APointFeatureOutsideItsGateIsRefused) {
  const geometry::Pose2D prior{1.0, 1.0, 0.0};
  const Eigen::Vector2d world(3.0, 2.0);  // seen at (2, 1) from the prior
  Eigen::Matrix2d cov = 1e-4 * Eigen::Matrix2d::Identity();
  EXPECT_TRUE(GatePoint({2.01, 1.0}, cov, world, prior, kPrior, 0.02, 5.99));
  EXPECT_NEAR(cov(0, 0), 1e-4 + 4e-4, 1e-12);
  Eigen::Matrix2d far = 1e-4 * Eigen::Matrix2d::Identity();
  EXPECT_FALSE(GatePoint({2.3, 1.0}, far, world, prior, kPrior, 0.02, 5.99));
  EXPECT_TRUE(GatePoint({2.3, 1.0}, far, world, prior, kPrior, 0.02, 0.0));  // no gate
}

}  // namespace
}  // namespace structloc::localisation_core
