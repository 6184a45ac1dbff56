// A map's error is the same in every scan that sees the same wall
// (map_error_memory.hpp): the memory's own arithmetic, the localiser giving a
// wall it has just fused less weight, and a tracker with perfect odometry
// driving past walls misdrawn by 3 cm, which stays nearer the truth with the
// memory than without (it no longer converges onto each wall's error).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "structloc/localisation_core/association/map_error_memory.hpp"
#include "structloc/localisation_core/tracking/pose_tracker.hpp"
#include "structloc/localisation_core/tracking/tracking_session_options.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "synthetic_scans.hpp"
#include "test_paths.hpp"

namespace structloc::localisation_core {
namespace {

const std::string kParams = std::string(STRUCTLOC_SOURCE_DIR) + "/maps/params/sick_lms2xx.xml";

TEST(MapErrorMemory, CountsFusedUsesThatFadeWithTravel) {
  MapErrorMemory memory;
  memory.Reset(3, 2.0);
  ASSERT_TRUE(memory.Enabled());
  EXPECT_DOUBLE_EQ(memory.MapErrorScale(1), 1.0);
  memory.RememberFused(1);
  memory.RememberFused(1);
  EXPECT_DOUBLE_EQ(memory.MapErrorScale(1), 3.0);
  EXPECT_DOUBLE_EQ(memory.MapErrorScale(0), 1.0);
  memory.Travel(2.0);  // one correlation length: the uses fade by e
  EXPECT_NEAR(memory.MapErrorScale(1), 1.0 + 2.0 / std::exp(1.0), 1e-12);
  memory.Travel(1e300);
  EXPECT_DOUBLE_EQ(memory.MapErrorScale(1), 1.0);
  // Slots outside the map and a memory that is off change nothing.
  memory.RememberFused(-1);
  memory.RememberFused(3);
  EXPECT_DOUBLE_EQ(memory.MapErrorScale(3), 1.0);
  memory.Reset(3, 0.0);
  EXPECT_FALSE(memory.Enabled());
  memory.RememberFused(1);
  EXPECT_DOUBLE_EQ(memory.MapErrorScale(1), 1.0);
}

// The map as a survey gets it wrong: every wall moved along its normal by a
// seeded 3 cm (1 sigma), every pillar by as much in each axis. The errors stay
// the same from scan to scan.
world_model::WorldModel Misdrawn(const world_model::WorldModel& world) {
  std::mt19937 rng(2026);
  std::normal_distribution<double> error(0.0, 0.03);
  std::vector<world_model::Wall> walls;
  for (const auto& w : world.Walls()) {
    const Eigen::Vector2d along = (w.b - w.a).normalized();
    const Eigen::Vector2d shift = error(rng) * Eigen::Vector2d(-along.y(), along.x());
    walls.push_back(world_model::MakeWall(w.id, w.a + shift, w.b + shift));
  }
  std::vector<world_model::Cylinder> cylinders;
  for (auto c : world.Cylinders()) {
    c.centre += Eigen::Vector2d(error(rng), error(rng));
    cylinders.push_back(c);
  }
  return world_model::WorldModel(world.Name(), walls, {}, cylinders);
}

const world_model::WorldModel& Office() {
  static const auto world =
      world_model::LoadWorldModel(std::string(STRUCTLOC_SOURCE_DIR) + "/maps/office_floor.xml");
  return world;
}

// The same scan, fused again and again at one place: the features' information
// falls as the memory counts the map's error in; driving far away restores it.
TEST(MapErrorMemory, TheLocaliserWeighsAWallItJustFusedLess) {
  auto options = LoadLocaliserOptions(kParams);
  options.map_error_travel_m = 2.0;
  Localiser localiser(Office(), options);
  const auto scene = world_model::Scene::FromWorld(Office());
  std::mt19937 rng(3);
  const geometry::Pose2D pose{8.0, 6.0, 0.3};
  const auto scan = testing::CastScan(scene, pose, {361, geometry::kPi, 30.0, 0.005}, rng);
  UpdateInput in;
  in.scan = scan.View();
  in.odometry_pose = pose;
  in.odometry_covariance = Eigen::Vector3d(0.0025, 0.0025, 0.001).asDiagonal();
  std::vector<double> information;
  for (int k = 0; k < 4; ++k) {
    const auto& r = localiser.Update(in);
    ASSERT_GT(r.Matched(), 2);
    information.push_back(r.information.trace());
    localiser.RememberFused();
  }
  for (size_t k = 1; k < information.size(); ++k) EXPECT_LT(information[k], information[k - 1]);
  // 40 correlation lengths away and back: the walls' errors are new again.
  in.odometry_pose = {8.0 + 80.0, 6.0, 0.3};
  localiser.Update(in);
  in.odometry_pose = pose;
  EXPECT_NEAR(localiser.Update(in).information.trace(), information[0], 1e-6 * information[0]);
}

// Perfect odometry, slowly (2 m in 200 scans) along the corridor of a building
// whose map is misdrawn: the RMS position error over the run.
double RmsError(double map_error_travel_m) {
  const world_model::WorldModel map = Misdrawn(Office());
  const auto truth_scene = world_model::Scene::FromWorld(Office());
  auto localiser_options = LoadLocaliserOptions(kParams);
  localiser_options.map_error_travel_m = map_error_travel_m;
  PoseTracker tracker(map, localiser_options, LoadSessionOptions(kParams).tracker);
  std::mt19937 rng(11);
  auto pose_at = [](double t) { return geometry::Pose2D{1.0 + 0.1 * t, 6.0, 0.0}; };
  EXPECT_FALSE(tracker.AddOdometry(0.0, pose_at(0.0)));
  EXPECT_FALSE(
      tracker.SetInitialPose(0.0, pose_at(0.0), Eigen::Vector3d(1e-4, 1e-4, 1e-5).asDiagonal()));
  double sum2 = 0.0;
  const int steps = 200;
  for (int k = 1; k <= steps; ++k) {  // 20 s, 2 m
    const double t = 0.1 * k;
    EXPECT_FALSE(tracker.AddOdometry(t, pose_at(t)));
    const auto cast =
        testing::CastScan(truth_scene, pose_at(t), {361, geometry::kPi, 30.0, 0.005}, rng);
    const auto out = tracker.ProcessScan(testing::TrackerInput(cast, t), 1.0);
    EXPECT_EQ(out.verdict, PoseTracker::ScanVerdict::kProcessed);
    const geometry::Pose2D truth = pose_at(t), estimate = out.pose.pose;
    sum2 += std::pow(estimate.x - truth.x, 2) + std::pow(estimate.y - truth.y, 2);
  }
  return std::sqrt(sum2 / steps);
}

TEST(MapErrorMemory, PerfectOdometryPastAMisdrawnMapStaysNearerTheTruth) {
  const double independent = RmsError(0.0), remembered = RmsError(2.0);
  std::cout << "perfect odometry, walls misdrawn by 3 cm (1 sigma): RMS error "
            << 1000 * independent << " mm with every scan's map error independent, "
            << 1000 * remembered << " mm with it counted once per 2 m of travel\n";
  EXPECT_LT(remembered, 0.85 * independent);
}

}  // namespace
}  // namespace structloc::localisation_core
