// Relations files and the relation metric (relations_reader.hpp,
// relation_error.hpp): a relation is read as the pose at t2 in the frame at
// t1; a path is judged by the relative poses it gives against them, its
// global frame and slow drift aside; a malformed line is refused with its
// file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "structloc/log_formats/relations_reader.hpp"
#include "structloc/replay/relation_error.hpp"
#include "temp_dir.hpp"

namespace structloc {
namespace {

TEST(Relations, APathIsJudgedByItsRelativePosesOnly) {
  const testing::TempDir temp;
  const std::string path = temp / "r.relations";
  {
    std::ofstream out(path);
    // 1 m ahead and turned 90 deg; then 1 m ahead again.
    out << "10.0 11.0 1.0 0.0 0.00000  0.00000 0.00000 1.5707963267948966\n";
    out << "11.0 12.0 1.0 0.0 0 0 0 0\n";
  }
  const auto relations = log_formats::ReadRelations(path);
  ASSERT_EQ(relations.size(), 2u);
  // The path: in a frame turned and shifted (does not count); the second
  // step 0.1 m short (counts).
  const geometry::Pose2D frame{5.0, -3.0, 0.7};
  std::vector<log_formats::StampedPose> trajectory = {
      {10.0, geometry::Compose(frame, {0, 0, 0})},
      {11.0, geometry::Compose(frame, {1, 0, 1.5707963267948966})},
      {12.0, geometry::Compose(frame, {1, 0.9, 1.5707963267948966})}};
  const auto e = replay::CompareRelations(trajectory, relations);
  EXPECT_EQ(e.used, 2u);
  EXPECT_NEAR(e.translation_mean_m, 0.05, 1e-9);
  EXPECT_NEAR(e.translation_std_m, 0.05, 1e-9);
  EXPECT_NEAR(e.rotation_mean_rad, 0.0, 1e-9);
  // A relation whose stamp the path lacks is counted apart.
  trajectory.pop_back();
  EXPECT_EQ(replay::CompareRelations(trajectory, relations).missing, 1u);
}

TEST(Relations, AMalformedLineIsRefusedWithItsLine) {
  const testing::TempDir temp;
  const std::string path = temp / "bad.relations";
  {
    std::ofstream out(path);
    out << "10.0 11.0 1.0 0.0 0 0 0 0\n# a comment\n10.0 11.0 1.0 nan 0 0 0\n";
  }
  try {
    log_formats::ReadRelations(path);
    FAIL() << "accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path + ":3:"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace structloc
