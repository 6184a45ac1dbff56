// Which model features the localiser expects follows from the scan itself
// (thesis 3.5.3): its angular range and range limits, not a field-of-view
// option. Also checks that testing occlusion against the surfaces near the
// sensor only gives exactly what testing every surface gives.
#include <gtest/gtest.h>

#include "test_paths.hpp"

#include <algorithm>
#include <random>

#include "structloc/localisation_core/expectation/scan_visibility.hpp"
#include "structloc/localisation_core/localiser/localiser.hpp"
#include "synthetic_scans.hpp"

namespace structloc::localisation_core {
namespace {

using geometry::kPi;

// A 6 m x 6 m room around the origin: walls ahead (0), behind (1), left (2), right (3).
world_model::WorldModel Room() {
  return world_model::WorldModel(
      "room",
      {world_model::MakeWall(0, {3, -3}, {3, 3}), world_model::MakeWall(1, {-3, -3}, {-3, 3}),
       world_model::MakeWall(2, {-3, 3}, {3, 3}), world_model::MakeWall(3, {-3, -3}, {3, -3})},
      {}, {});
}

std::vector<int> VisibleWalls(const world_model::WorldModel& world, const LocaliserOptions& options,
                              const ScanView& scan) {
  const auto scene = world_model::Scene::FromWorld(world);
  world_model::Visibility v;
  world_model::ComputeVisibility(world, scene, {0, 0, 0}, ScanVisibility(options, scan), v);
  std::vector<int> walls;
  for (const auto& w : v.walls) walls.push_back(w.index);
  return walls;
}

TEST(ScanVisibility, TheScansAngularRangeDecidesWhichWallsAreExpected) {
  const auto world = Room();
  const auto scene = world_model::Scene::FromWorld(world);
  const auto options =
      LoadLocaliserOptions(testing::SourcePath("maps/params/sick_lms2xx.xml"));  // one file
  std::mt19937 rng(3);
  const auto full = testing::CastScan(scene, {0, 0, 0}, {720, 2 * kPi, 30.0, 0.005}, rng);
  const auto half = testing::CastScan(scene, {0, 0, 0}, {361, kPi, 30.0, 0.005}, rng);
  // The wall behind the robot only for the full circle.
  EXPECT_EQ(VisibleWalls(world, options, full.View()), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(VisibleWalls(world, options, half.View()), (std::vector<int>{0, 2, 3}));
  // The scan's own range limit counts too: nothing lies within 2.5 m.
  auto short_range = half.View();
  short_range.range_max = 2.5;
  EXPECT_TRUE(VisibleWalls(world, options, short_range).empty());

  // The localiser expects what the scan can show, with the same options.
  Localiser localiser(world, options);
  UpdateInput in;
  in.odometry_pose = {0.02, -0.01, 0.01};
  in.odometry_covariance = Eigen::Vector3d(0.0025, 0.0025, 0.001).asDiagonal();
  in.scan = full.View();
  EXPECT_EQ(localiser.Update(in).Kind("walls")->expected, 4);
  in.scan = half.View();
  const auto& r = localiser.Update(in);
  EXPECT_EQ(r.Kind("walls")->expected, 3);
  EXPECT_EQ(r.Kind("walls")->Matched(), 3);
  EXPECT_FALSE(r.lost);
}

// Visible length of one wall with every surface of the scene tested for
// occlusion, sample by sample as ComputeVisibility samples (full circle).
double ReferenceVisibleLength(const world_model::Wall& w, const world_model::Scene& scene,
                              const Eigen::Vector2d& origin,
                              const world_model::VisibilityOptions& o) {
  const double length = w.Length();
  const auto intervals =
      static_cast<int64_t>(std::max(1.0, std::ceil(length / o.sample_spacing_m)));
  const Eigen::Vector2d normal(std::cos(w.line.alpha), std::sin(w.line.alpha));
  double visible = 0.0;
  for (int64_t k = 0; k <= intervals; ++k) {
    const Eigen::Vector2d p =
        w.a + (w.b - w.a) * (static_cast<double>(k) / static_cast<double>(intervals));
    const double range = (p - origin).norm();
    if (range < o.min_range_m || range > o.max_range_m) continue;
    if (std::abs((p - origin).normalized().dot(normal)) < std::cos(o.max_incidence_rad)) continue;
    if (scene.Occluded(origin, p, o.occlusion_margin_m)) continue;
    visible += length / static_cast<double>(intervals);
  }
  return visible;
}

TEST(ScanVisibility, OcclusionByNearbySurfacesOnlyEqualsTestingEverySurface) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-15.0, 15.0), offset(-3.0, 3.0);
  std::vector<world_model::Wall> walls;
  for (int i = 0; i < 150; ++i) {
    const Eigen::Vector2d a(coordinate(rng), coordinate(rng));
    walls.push_back(world_model::MakeWall(i, a, a + Eigen::Vector2d(offset(rng), offset(rng))));
  }
  std::vector<world_model::Cylinder> cylinders;
  for (int i = 0; i < 10; ++i) cylinders.push_back({i, {coordinate(rng), coordinate(rng)}, 0.2});
  const world_model::WorldModel world("clutter", walls, {}, cylinders);
  const auto scene = world_model::Scene::FromWorld(world);
  world_model::VisibilityOptions o;
  o.max_range_m = 8.0;
  o.min_visible_length_m = 0.0;
  world_model::Visibility v;
  int compared = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const geometry::Pose2D sensor{coordinate(rng), coordinate(rng), 0.0};
    world_model::ComputeVisibility(world, scene, sensor, o, v);
    std::vector<double> length(world.Walls().size(), 0.0);
    for (const auto& w : v.walls) length[static_cast<size_t>(w.index)] = w.visible_length_m;
    for (size_t i = 0; i < world.Walls().size(); ++i) {
      EXPECT_DOUBLE_EQ(length[i],
                       ReferenceVisibleLength(world.Walls()[i], scene, sensor.Translation(), o))
          << "wall " << i << " trial " << trial;
      compared += length[i] > 0.0;
    }
    for (size_t i = 0; i < world.Cylinders().size(); ++i) {
      const auto& c = world.Cylinders()[i];
      const Eigen::Vector2d to_centre = c.centre - sensor.Translation();
      const Eigen::Vector2d near = c.centre - c.radius * to_centre.normalized();
      const double range = (near - sensor.Translation()).norm();
      const bool expected = to_centre.norm() > c.radius && range >= o.min_range_m &&
                            range <= o.max_range_m &&
                            !scene.Occluded(sensor.Translation(), near, o.occlusion_margin_m);
      EXPECT_EQ(std::count(v.cylinders.begin(), v.cylinders.end(), static_cast<int>(i)),
                expected ? 1 : 0);
    }
  }
  EXPECT_GT(compared, 100);  // the comparison covered many partly hidden walls
}

}  // namespace
}  // namespace structloc::localisation_core
