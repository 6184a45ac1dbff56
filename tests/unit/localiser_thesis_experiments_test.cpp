// The thesis' own experiments on synthetic scans: repeatability in the
// dead-end corridor (4.3, Tables 4-7) and robustness to an unmodelled box
// hiding 0..100 % of a wall (4.4, Tables 8-9).
#include <gtest/gtest.h>

#include "test_paths.hpp"

#include <cstdio>

#include "structloc/localisation_core/localiser/localiser.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "synthetic_scans.hpp"

namespace structloc::localisation_core {
namespace {

using geometry::kPi;
using geometry::Pose2D;

struct Stats {
  double mean[3] = {0, 0, 0}, std[3] = {0, 0, 0};
};

Stats Compute(const std::vector<Pose2D>& poses) {
  Stats s;
  const double n = static_cast<double>(poses.size());
  for (const auto& p : poses) {
    s.mean[0] += p.x / n;
    s.mean[1] += p.y / n;
    s.mean[2] += p.theta / n;
  }
  for (const auto& p : poses) {
    const double d[3] = {p.x - s.mean[0], p.y - s.mean[1], p.theta - s.mean[2]};
    for (int k = 0; k < 3; ++k) s.std[k] += d[k] * d[k] / (n - 1);
  }
  for (double& v : s.std) v = std::sqrt(v);
  return s;
}

// 100 updates from the thesis' start odometry (Table 4), each with a new scan
// of 300 beams over 2 pi with 5 mm range noise; the estimate overwrites the
// odometry as in the thesis.
Stats Repeatability(const std::string& params) {
  const auto world = world_model::LoadWorldModel(testing::SourcePath("maps/dead_end_corridor.xml"));
  const auto scene = world_model::Scene::FromWorld(world);
  Localiser localiser(world, LoadLocaliserOptions(testing::SourcePath(params)));
  const Pose2D truth{1.0, 0.9, 0.0};
  std::mt19937 rng(2024);
  Pose2D estimate{1.02, 0.89, 0.001};
  std::vector<Pose2D> poses;
  for (int i = 0; i < 100; ++i) {
    const auto scan = testing::CastScan(scene, truth, {300, 2 * kPi, 30.0, 0.005}, rng);
    UpdateInput in;
    in.scan = scan.View();
    in.odometry_pose = estimate;
    in.odometry_covariance = Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 0.05 * 0.05).asDiagonal();
    const auto& r = localiser.Update(in);
    EXPECT_FALSE(r.lost) << ToString(r.lost_reason);
    EXPECT_EQ(r.Kind("walls")->Matched(), 3);
    estimate = r.pose;
    poses.push_back(r.pose);
  }
  return Compute(poses);
}

TEST(ThesisRepeatability, DeadEndCorridorBeatsTheThesisTable7) {
  for (const auto* params : {"maps/params/thesis_table6.xml", "maps/params/table6_weighted.xml"}) {
    const Stats s = Repeatability(params);
    std::printf("%s: std x %.2f mm, y %.2f mm, theta %.3f deg; mean error x %.2f mm, y %.2f mm\n",
                params, 1e3 * s.std[0], 1e3 * s.std[1], s.std[2] * 180 / kPi,
                1e3 * (s.mean[0] - 1.0), 1e3 * (s.mean[1] - 0.9));
    EXPECT_LT(s.std[0], 0.003) << params;
    EXPECT_LT(s.std[1], 0.004) << params;
    EXPECT_LT(s.std[2], 0.3 * kPi / 180) << params;
    // The thesis measured scatter only. Its linear mode averages corner
    // intersections of windows that partly straddle the corner, which biases x
    // by a few millimetres; the weighted mode does not use those (redundant) corners.
    const double bias_limit =
        std::string(params).find("weighted") != std::string::npos ? 0.001 : 0.01;
    EXPECT_NEAR(s.mean[0], 1.0, bias_limit) << params;
    EXPECT_NEAR(s.mean[1], 0.9, bias_limit) << params;
  }
}

// Two perpendicular walls; an unmodelled box 0.6 m in front of wall 2 hides
// `fraction` of it as seen from the robot.
TEST(ThesisRobustness, AnUnmodelledBoxHidingWall2NeverMakesItDiverge) {
  const auto world = world_model::LoadWorldModel(testing::SourcePath("maps/robustness_room.xml"));
  const Pose2D truth{1.5, 1.5, 0.3};
  for (double fraction : {0.0, 0.3, 0.6, 0.8, 1.0}) {
    world_model::Scene scene = world_model::Scene::FromWorld(world);
    if (fraction > 0) {
      // The box face at y = 0.6 covers the rays to wall 2 (y = 0) for x in [0, 3 fraction].
      const double y = 0.6, k = (truth.y - y) / truth.y;
      const double xa = truth.x + k * (0.0 - truth.x) - 0.05;
      const double xb = truth.x + k * (3.0 * fraction - truth.x) + (fraction >= 1.0 ? 0.05 : 0.0);
      scene.Add(testing::Box({0.5 * (xa + xb), y - 0.1}, xb - xa, 0.2, 0.0));
    }
    Localiser localiser(
        world, LoadLocaliserOptions(testing::SourcePath("maps/params/table6_weighted.xml")));
    std::mt19937 rng(99);
    Pose2D estimate{truth.x + 0.03, truth.y - 0.02, truth.theta + 0.02};
    std::vector<Pose2D> poses;
    bool reported_unobservable = false;
    Eigen::Vector3d weak = Eigen::Vector3d::Zero();
    for (int i = 0; i < 20; ++i) {
      const auto scan = testing::CastScan(scene, truth, {300, 2 * kPi, 30.0, 0.005}, rng);
      UpdateInput in;
      in.scan = scan.View();
      in.odometry_pose = estimate;
      in.odometry_covariance = Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 0.05 * 0.05).asDiagonal();
      const auto& r = localiser.Update(in);
      ASSERT_TRUE(geometry::IsFinite(r.pose));
      if (r.lost_reason == LostReason::kUnderdetermined) {
        reported_unobservable = true;
        weak = r.weak_direction;
      }
      estimate = r.pose;
      poses.push_back(r.pose);
    }
    const Stats s = Compute(poses);
    std::printf(
        "occlusion %3.0f %%: std x %.2f mm, y %.2f mm, theta %.3f deg, final error "
        "(%.1f, %.1f) mm, unobservable reported: %s\n",
        100 * fraction, 1e3 * s.std[0], 1e3 * s.std[1], s.std[2] * 180 / kPi,
        1e3 * (estimate.x - truth.x), 1e3 * (estimate.y - truth.y),
        reported_unobservable ? "yes" : "no");
    // Never diverges: the estimate stays within the start error and stable.
    EXPECT_LT(std::abs(estimate.x - truth.x), 0.01) << fraction;
    EXPECT_LT(std::abs(estimate.y - truth.y), 0.03) << fraction;
    EXPECT_LT(s.std[0], 0.01) << fraction;
    EXPECT_LT(s.std[2], kPi / 180) << fraction;
    if (fraction >= 1.0) {
      // Wall 2 unseen: y is what the features cannot give, and it is said.
      EXPECT_TRUE(reported_unobservable);
      EXPECT_GT(std::abs(weak.y()), 0.9) << weak.transpose();
    } else if (fraction <= 0.6) {
      // At 80 % only ~0.6 m of wall 2 is left, a window or two after thinning:
      // some updates then honestly report y as undetermined.
      EXPECT_FALSE(reported_unobservable) << fraction;
      EXPECT_LT(std::abs(estimate.y - truth.y), 0.005) << fraction;
    }
  }
}

}  // namespace
}  // namespace structloc::localisation_core
