// Geometry primitives, the world model and its XML reader, ray casting and
// visibility, against hand-computed values.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "config_test_support.hpp"
#include "structloc/world_model/ray_cast.hpp"
#include "structloc/world_model/visibility.hpp"
#include "structloc/world_model/world_model_xml.hpp"

namespace structloc {
namespace {

using geometry::kPi;
using geometry::Pose2D;

TEST(Geometry, WrapAngleIsHalfOpenAtMinusPi) {
  EXPECT_DOUBLE_EQ(geometry::WrapAngle(kPi), kPi);
  EXPECT_DOUBLE_EQ(geometry::WrapAngle(-kPi), kPi);
  EXPECT_NEAR(geometry::WrapAngle(3 * kPi + 0.1), -kPi + 0.1, 1e-12);
  EXPECT_NEAR(geometry::WrapAngle(-7.0), -7.0 + 2 * kPi, 1e-12);
}

TEST(Geometry, ComposeInverseAndBetween) {
  const Pose2D a{1.0, 2.0, 0.5}, b{-0.3, 0.7, -2.9};
  const Pose2D ab = geometry::Compose(a, b);
  const Pose2D back = geometry::Between(a, ab);
  EXPECT_NEAR(back.x, b.x, 1e-12);
  EXPECT_NEAR(back.y, b.y, 1e-12);
  EXPECT_NEAR(back.theta, b.theta, 1e-12);
  const Eigen::Vector2d p(0.4, -1.2);
  EXPECT_TRUE(a.ApplyInverse(a.Apply(p)).isApprox(p, 1e-12));
}

TEST(Geometry, LineThroughAndInFrame) {
  const auto l = geometry::LineThrough({0.0, 2.0}, {5.0, 2.0});  // y = 2
  EXPECT_NEAR(l.r, 2.0, 1e-12);
  EXPECT_NEAR(l.alpha, kPi / 2, 1e-12);
  const auto seen = geometry::LineInFrame(l, {1.0, 0.5, 0.3});
  EXPECT_NEAR(seen.r, 1.5, 1e-12);
  EXPECT_NEAR(seen.alpha, kPi / 2 - 0.3, 1e-12);
  const auto behind = geometry::LineInFrame(l, {1.0, 3.0, 0.0});  // robot above the line
  EXPECT_NEAR(behind.r, 1.0, 1e-12);
  EXPECT_NEAR(behind.alpha, -kPi / 2, 1e-12);
}

TEST(WorldModel, EveryShippedMapLoads) {
  int count = 0;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(STRUCTLOC_SOURCE_DIR) + "/maps")) {
    if (e.path().extension() != ".xml") continue;
    const auto world = world_model::LoadWorldModel(e.path().string());
    EXPECT_FALSE(world.Name().empty());
    ++count;
  }
  EXPECT_GE(count, 3);
}

TEST(WorldModel, DerivesCornersWhereWallEndsMeetAtRightAngles) {
  const auto world = world_model::LoadWorldModel(std::string(STRUCTLOC_SOURCE_DIR) +
                                                 "/maps/dead_end_corridor.xml");
  ASSERT_EQ(world.Walls().size(), 3u);
  ASSERT_EQ(world.Corners().size(), 2u);  // (0.1, 0.1) and (0.1, 2.21)
  EXPECT_TRUE(world.Corners()[0].derived);
  EXPECT_NEAR(world.Walls()[0].line.r, 0.1, 1e-12);
  EXPECT_NEAR(world.Walls()[0].line.alpha, kPi / 2, 1e-12);
  EXPECT_NEAR(world.Walls()[1].line.r, 0.1, 1e-12);
  EXPECT_NEAR(std::abs(world.Walls()[1].line.alpha), 0.0, 1e-12);
  EXPECT_NEAR(world.Walls()[2].line.r, 2.21, 1e-12);
  // Walls at 45 degrees do not make a corner.
  const auto skew = world_model::WorldModel(
      "s", {world_model::MakeWall(0, {0, 0}, {1, 0}), world_model::MakeWall(1, {1, 0}, {2, 1})}, {},
      {});
  EXPECT_TRUE(skew.Corners().empty());
}

struct BadWorld {
  const char* tag;
  const char* text;
  const char* problem;
};
class BadWorldFile : public ::testing::TestWithParam<BadWorld> {};

TEST_P(BadWorldFile, IsRejectedWithFileLineAndProblem) {
  testing::ExpectRejected(GetParam().text, GetParam().problem,
                          [](const std::string& path) { world_model::LoadWorldModel(path); });
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadWorldFile,
    ::testing::Values(
        BadWorld{"ZeroLength", "<world name='w'>\n<wall x1='1' y1='1' x2='1' y2='1'/></world>",
                 ":2: <wall>: zero-length wall"},
        BadWorld{"NegativeRadius", "<world name='w'><cylinder x='1' y='1' radius='-0.2'/></world>",
                 "radius must be > 0"},
        BadWorld{"UnknownAttribute",
                 "<world name='w'><wall x1='0' y1='0' x2='1' y2='0' z='3'/></world>",
                 "unknown attribute(s): z"},
        BadWorld{"MissingValue", "<world name='w'><corner x='1'/></world>", "missing attribute y"},
        BadWorld{"NotANumber", "<world name='w'><corner x='1' y='abc'/></world>",
                 "y=\"abc\" is not a finite number"},
        BadWorld{"NaN", "<world name='w'><corner x='nan' y='1'/></world>", "not a finite number"},
        BadWorld{"UnknownElement", "<world name='w'><door x='1' y='1'/></world>",
                 "unknown element"},
        BadWorld{"Empty", "<world name='w'/>", "no walls, corners or cylinders"},
        BadWorld{"DuplicateId",
                 "<world name='w'><corner id='1' x='0' y='0'/><corner id='1' x='1' y='0'/></world>",
                 "duplicate corner id 1"},
        BadWorld{"WrongRoot", "<map name='w'/>", "expected <world>"},
        BadWorld{"Malformed", "<world name='w'><wall x1='0'</world>", "malformed XML"}),
    [](const auto& info) { return std::string(info.param.tag); });

TEST(RayCast, HandComputedRanges) {
  world_model::Scene scene;
  scene.segments.push_back({{2, -5}, {2, 5}});  // x = 2
  scene.segments.push_back({{-5, 3}, {5, 3}});  // y = 3
  scene.circles.push_back({{-3, 0}, 0.5});
  const Eigen::Vector2d o(0, 0);
  EXPECT_NEAR(scene.Cast(o, {1, 0}, 30), 2.0, 1e-12);
  EXPECT_NEAR(scene.Cast(o, {0, 1}, 30), 3.0, 1e-12);
  const Eigen::Vector2d diag = Eigen::Vector2d(1, 1).normalized();  // hits x = 2 first at 2*sqrt2
  EXPECT_NEAR(scene.Cast(o, diag, 30), 2.0 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(scene.Cast(o, {-1, 0}, 30), 2.5, 1e-12);  // cylinder in front
  EXPECT_TRUE(std::isinf(scene.Cast(o, {0, -1}, 30)));
  EXPECT_TRUE(std::isinf(scene.Cast(o, {1, 0}, 1.5)));  // beyond max range
  // Occlusion order: the nearer of two surfaces on one ray wins.
  scene.segments.push_back({{1, -1}, {1, 1}});
  EXPECT_NEAR(scene.Cast(o, {1, 0}, 30), 1.0, 1e-12);
}

TEST(Visibility, RangeOcclusionAndFieldOfView) {
  const world_model::WorldModel world(
      "v",
      {world_model::MakeWall(0, {-5, 2}, {5, 2}), world_model::MakeWall(1, {-5, -6}, {5, -6}),
       world_model::MakeWall(2, {-1, -1}, {1, -1}), world_model::MakeWall(3, {-1, -3}, {1, -3})},
      {}, {{0, {3, 0}, 0.3}});
  const world_model::Scene scene = world_model::Scene::FromWorld(world);
  world_model::VisibilityOptions o;
  o.min_range_m = 0.1;
  o.max_range_m = 4.0;
  world_model::Visibility v;
  world_model::ComputeVisibility(world, scene, {0, 0, 0}, o, v);
  std::vector<int> walls;
  for (const auto& w : v.walls) walls.push_back(w.index);
  // Wall 1 is beyond range, wall 3 hidden behind wall 2.
  EXPECT_EQ(walls, (std::vector<int>{0, 2}));
  EXPECT_EQ(v.cylinders, (std::vector<int>{0}));
  o.view_min_rad = -kPi / 6;  // +-30 deg along +x: wall 0 only beyond range, so only the pillar
  o.view_max_rad = kPi / 6;
  world_model::ComputeVisibility(world, scene, {0, 0, 0}, o, v);
  EXPECT_TRUE(v.walls.empty());
  EXPECT_EQ(v.cylinders, (std::vector<int>{0}));
}

}  // namespace
}  // namespace structloc
