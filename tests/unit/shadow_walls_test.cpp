// Shadow walls (shadow_walls.hpp): a copy of a wall a few centimetres beside
// it, seen from the same side, goes; the two faces of a partition stay.
#include <gtest/gtest.h>

#include "structloc/map_building/shadow_walls.hpp"

namespace structloc::map_building {
namespace {

FittedWall Wall(double x1, double y1, double x2, double y2, double view_x, double view_y) {
  FittedWall w;
  w.a = {x1, y1};
  w.b = {x2, y2};
  w.viewpoint = {view_x, view_y};
  return w;
}

TEST(ShadowWalls, ACopySeenFromTheSameSideIsDropped) {
  std::vector<FittedWall> walls = {Wall(0, 0, 5, 0, 2, 3), Wall(1, 0.05, 3, 0.03, 2, 2)};
  EXPECT_EQ(DropShadowWalls(walls, ShadowWallOptions{}), 1u);
  ASSERT_EQ(walls.size(), 1u);
  EXPECT_DOUBLE_EQ(walls[0].b.x(), 5.0);  // the longer stays
}

TEST(ShadowWalls, TheFacesOfAPartitionStay) {
  std::vector<FittedWall> walls = {Wall(0, 0, 5, 0, 2, -3), Wall(0, 0.1, 5, 0.1, 2, 3)};
  EXPECT_EQ(DropShadowWalls(walls, ShadowWallOptions{}), 0u);
  EXPECT_EQ(walls.size(), 2u);
}

TEST(ShadowWalls, WallsApartTurnedOrBesideEachOtherStay) {
  const ShadowWallOptions o;
  std::vector<FittedWall> far = {Wall(0, 0, 5, 0, 2, 3), Wall(1, 0.3, 3, 0.3, 2, 3)};
  std::vector<FittedWall> turned = {Wall(0, 0, 5, 0, 2, 3), Wall(1, 0, 3, 0.5, 2, 3)};
  std::vector<FittedWall> beyond = {Wall(0, 0, 5, 0, 2, 3), Wall(4.5, 0.05, 7, 0.05, 6, 3)};
  EXPECT_EQ(DropShadowWalls(far, o), 0u);
  EXPECT_EQ(DropShadowWalls(turned, o), 0u);
  EXPECT_EQ(DropShadowWalls(beyond, o), 0u);  // only 0.5 of 2.5 m alongside
}

TEST(ShadowWalls, ZeroOffsetKeepsEveryWall) {
  std::vector<FittedWall> walls = {Wall(0, 0, 5, 0, 2, 3), Wall(1, 0.01, 3, 0.01, 2, 2)};
  ShadowWallOptions o;
  o.max_offset_m = 0.0;
  EXPECT_EQ(DropShadowWalls(walls, o), 0u);
}

}  // namespace
}  // namespace structloc::map_building
