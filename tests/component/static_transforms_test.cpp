// The laser's mounting from the static transforms a robot publishes: the
// chain from the base frame down to the laser composed in the plane, and no
// mounting while the chain is incomplete, loops or holds a non-finite value.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/dds_common/static_transforms.hpp"

namespace structloc::dds_common {
namespace {

tf2_msgs::msg::TFMessage One(const std::string& parent, const std::string& child, double x,
                             double y, double yaw) {
  geometry_msgs::msg::TransformStamped t;
  t.header().frame_id(parent);
  t.child_frame_id(child);
  t.transform().translation().x(x);
  t.transform().translation().y(y);
  t.transform().rotation(ToQuaternion(yaw));
  tf2_msgs::msg::TFMessage m;
  m.transforms().push_back(t);
  return m;
}

TEST(StaticTransforms, ADirectTransformIsTheMounting) {
  StaticTransforms statics;
  statics.Add(One("base_link", "laser", 0.2, -0.1, 0.3));
  std::string path;
  const auto mount = statics.Chain("base_link", "laser", path);
  ASSERT_TRUE(mount.has_value());
  EXPECT_NEAR(mount->x, 0.2, 1e-12);
  EXPECT_NEAR(mount->y, -0.1, 1e-12);
  EXPECT_NEAR(mount->theta, 0.3, 1e-12);
  EXPECT_EQ(path, "base_link -> laser");
}

TEST(StaticTransforms, AChainThroughFramesBetweenIsComposedInOrder) {
  StaticTransforms statics;
  statics.Add(One("laser_mount", "laser", 0.2, 0.0, 0.0));  // in any order, several messages
  std::string path;
  EXPECT_FALSE(statics.Chain("base_link", "laser", path).has_value()) << "incomplete";
  statics.Add(One("base_link", "laser_mount", 0.1, 0.0, geometry::kHalfPi));
  const auto mount = statics.Chain("base_link", "laser", path);
  ASSERT_TRUE(mount.has_value());
  EXPECT_NEAR(mount->x, 0.1, 1e-12);  // 0.2 along the mount's x, which points along y
  EXPECT_NEAR(mount->y, 0.2, 1e-12);
  EXPECT_NEAR(mount->theta, geometry::kHalfPi, 1e-12);
  EXPECT_EQ(path, "base_link -> laser_mount -> laser");
}

TEST(StaticTransforms, NoMountingFromALoopANonFiniteValueOrAnotherBase) {
  StaticTransforms loop;
  loop.Add(One("a", "laser", 0.1, 0, 0));
  loop.Add(One("laser", "a", 0.1, 0, 0));
  std::string path;
  EXPECT_FALSE(loop.Chain("base_link", "laser", path).has_value());
  StaticTransforms broken;
  broken.Add(One("base_link", "laser", std::numeric_limits<double>::quiet_NaN(), 0, 0));
  EXPECT_FALSE(broken.Chain("base_link", "laser", path).has_value());
  StaticTransforms elsewhere;
  elsewhere.Add(One("base_footprint", "laser", 0.2, 0, 0));
  EXPECT_FALSE(elsewhere.Chain("base_link", "laser", path).has_value());
  EXPECT_FALSE(elsewhere.Chain("laser", "laser", path).has_value()) << "no transform at all";
}

// A peer flooding rt/tf_static with ever new frames fills a bounded table;
// the frames known before keep their transforms and the chain still holds.
TEST(StaticTransforms, EverNewFramesAreBoundedAndTheKnownChainKept) {
  StaticTransforms statics;
  statics.Add(One("base_link", "laser", 0.2, 0, 0));
  tf2_msgs::msg::TFMessage flood;
  for (size_t i = 0; i < StaticTransforms::kMaxFrames + 100; ++i) {
    geometry_msgs::msg::TransformStamped t;
    t.header().frame_id("base_link");
    t.child_frame_id("junk_" + std::to_string(i));
    flood.transforms().push_back(t);
  }
  statics.Add(flood);
  EXPECT_EQ(statics.Frames(), StaticTransforms::kMaxFrames);
  EXPECT_EQ(statics.Dropped(), 101u);                 // the laser's frame took one place
  statics.Add(One("base_link", "laser", 0.3, 0, 0));  // a known frame still updates
  std::string path;
  const auto mount = statics.Chain("base_link", "laser", path);
  ASSERT_TRUE(mount.has_value());
  EXPECT_NEAR(mount->x, 0.3, 1e-12);
}

TEST(StaticTransforms, TheNewestTransformOfAFrameWins) {
  StaticTransforms statics;
  statics.Add(One("base_link", "laser", 0.2, 0, 0));
  statics.Add(One("base_link", "laser", 0.3, 0, 0));
  std::string path;
  const auto mount = statics.Chain("base_link", "laser", path);
  ASSERT_TRUE(mount.has_value());
  EXPECT_NEAR(mount->x, 0.3, 1e-12);
}

}  // namespace
}  // namespace structloc::dds_common
