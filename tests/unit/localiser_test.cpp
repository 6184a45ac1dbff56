// The whole update: parameter files, rejection of bad input (never a NaN),
// de-skewing of a scan taken while moving, and the Kohonen strategy.
#include <gtest/gtest.h>

#include "test_paths.hpp"

#include <filesystem>
#include <sstream>

#include "structloc/localisation_core/features/corners/corner_extractor.hpp"
#include "structloc/localisation_core/features/walls/wall_extractor.hpp"
#include "structloc/localisation_core/localiser/localiser.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "synthetic_scans.hpp"
#include "temp_dir.hpp"
#include "whole_params.hpp"

namespace structloc::localisation_core {
namespace {

using geometry::kPi;
using geometry::Pose2D;

TEST(LocaliserOptions, EveryShippedParameterFileLoads) {
  int count = 0;
  for (const auto& e : std::filesystem::directory_iterator(testing::SourcePath("maps/params"))) {
    if (e.path().extension() != ".xml") continue;
    EXPECT_NO_THROW(LoadLocaliserOptions(e.path().string())) << e.path();
    ++count;
  }
  EXPECT_GE(count, 2);
  const auto thesis = LoadLocaliserOptions(testing::SourcePath("maps/params/thesis_table6.xml"));
  EXPECT_EQ(thesis.line_fit.window_points, 7);
  EXPECT_DOUBLE_EQ(thesis.prefilter.max_range_m, 4.0);
  EXPECT_EQ(thesis.solver.mode, SolverMode::kThesisLinear);
}

TEST(LocaliserOptions, DefaultsAreTheThesisTable6Values) {
  const LocaliserOptions o;
  EXPECT_EQ(o.line_fit.window_points, 7);
  EXPECT_DOUBLE_EQ(o.prefilter.max_range_m, 4.0);
  EXPECT_DOUBLE_EQ(o.prefilter.min_range_m, 0.5);
  EXPECT_DOUBLE_EQ(o.prefilter.max_neighbour_distance_m, 0.3);
  EXPECT_DOUBLE_EQ(o.prefilter.min_neighbour_distance_m, 0.06);
  const auto& walls = o.kinds.Get<WallKindOptions>().clusters;
  EXPECT_EQ(walls.min_cluster_size, 1);
  EXPECT_DOUBLE_EQ(walls.gate_alpha_rad, 0.2);
  EXPECT_DOUBLE_EQ(walls.gate_r_m, 0.2);
  EXPECT_NO_THROW(o.Validate());
}

std::string EditedCopy(const testing::TempDir& temp, const std::string& from,
                       const std::string& to) {
  return testing::EditedWholeParams(temp, testing::SourcePath("maps/params/thesis_table6.xml"),
                                    from, to);
}

TEST(LocaliserOptions, ListingCoversEveryKeyOfTheShippedFilesWithItsDefault) {
  std::ostringstream listing;
  PrintLocaliserOptions(listing);
  const std::string text = listing.str();
  // The thresholds of the pose update that used to be hard-coded are options now.
  for (const char* key : {"redundant_wall_distance_m", "redundant_min_sin", "quality_chi2_per_dof",
                          "max_beams", "refresh_angle_rad", "theta_rad"}) {
    EXPECT_NE(text.find(key), std::string::npos) << key;
  }
  const LocaliserOptions defaults;
  const auto& corners = defaults.kinds.Get<CornerKindOptions>().extraction;
  EXPECT_DOUBLE_EQ(corners.redundant_wall_distance_m, 0.05);
  EXPECT_DOUBLE_EQ(corners.redundant_min_sin, 0.5);
  EXPECT_DOUBLE_EQ(defaults.solver.quality_chi2_per_dof, 2.0);
  const auto thesis = LoadLocaliserOptions(testing::SourcePath("maps/params/thesis_table6.xml"));
  EXPECT_DOUBLE_EQ(thesis.kinds.Get<CornerKindOptions>().extraction.redundant_min_sin,
                   corners.redundant_min_sin);
}

TEST(LocaliserOptions, ValidateNamesSectionAndKeyOfAnOptionSetInCode) {
  LocaliserOptions o;
  o.kinds.Get<CornerKindOptions>().extraction.redundant_min_sin = 1.5;
  try {
    o.Validate();
    ADD_FAILURE() << "accepted redundant_min_sin = 1.5";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "corners: redundant_min_sin must be in [0, 1], not 1.5");
  }
}

TEST(LocaliserOptions, MissingUnknownAndInvalidKeysAreErrorsNamingTheKey) {
  const std::vector<std::pair<std::pair<std::string, std::string>, std::string>> cases = {
      {{" gate_r_m=\"0.2\"", ""}, "missing attribute gate_r_m"},
      {{"gate_r_m=\"0.2\"", "gate_r_m=\"0.2\" gate_x=\"1\""}, "unknown attribute(s): gate_x"},
      {{"gate_r_m=\"0.2\"", "gate_r_m=\"-1\""}, "walls: gate_r_m must be > 0"},
      {{"mode=\"thesis_linear\"", "mode=\"magic\""}, "mode must be weighted"},
      {{"<gates", "<gatez"}, "unknown element"},
      {{"window_points=\"7\"", "window_points=\"seven\""}, "is not an integer"},
  };
  for (const auto& [edit, problem] : cases) {
    const testing::TempDir temp;
    const std::string path = EditedCopy(temp, edit.first, edit.second);
    try {
      LoadLocaliserOptions(path);
      ADD_FAILURE() << "accepted " << edit.second;
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path + ":"), std::string::npos) << e.what();
    }
  }
}

class LocaliserFixture : public ::testing::Test {
 protected:
  LocaliserFixture()
      : world_(world_model::LoadWorldModel(testing::SourcePath("maps/dead_end_corridor.xml"))),
        scene_(world_model::Scene::FromWorld(world_)) {}
  world_model::WorldModel world_;
  world_model::Scene scene_;
  Pose2D truth_{1.0, 0.9, 0.0};
};

TEST_F(LocaliserFixture, BadInputIsRejectedWithAReasonAndNeverYieldsNaN) {
  Localiser localiser(world_, LocaliserOptions{});
  std::mt19937 rng(3);
  auto scan = testing::CastScan(scene_, truth_, {}, rng);
  UpdateInput in;
  in.scan = scan.View();
  in.odometry_pose = {1.02, 0.89, 0.001};
  in.odometry_covariance = Eigen::Vector3d(0.01, 0.01, 0.01).asDiagonal();
  auto expect_rejected = [&](const UpdateInput& input, const char* what) {
    const auto& r = localiser.Update(input);
    ASSERT_NE(r.rejection, nullptr) << what;
    EXPECT_TRUE(r.lost) << what;
    EXPECT_TRUE(geometry::IsFinite(r.pose)) << what;
    EXPECT_TRUE(r.covariance.allFinite()) << what;
  };
  UpdateInput bad = in;
  bad.scan.count = 0;
  expect_rejected(bad, "empty");
  bad = in;
  bad.scan.angle_increment = 0.0;
  expect_rejected(bad, "zero increment");
  bad = in;
  bad.scan.angle_increment = NAN;
  expect_rejected(bad, "nan increment");
  bad = in;
  bad.odometry_pose.x = NAN;
  expect_rejected(bad, "nan prior");
  bad = in;
  bad.odometry_covariance(0, 0) = -1;
  expect_rejected(bad, "negative covariance");
  BeamMotion wrong;
  wrong.Resize(3);
  bad = in;
  bad.motion = &wrong;
  expect_rejected(bad, "motion size");
  // A scan of only special values is processed, counted, and reported lost.
  std::vector<float> junk(300, std::numeric_limits<float>::quiet_NaN());
  for (size_t i = 0; i < junk.size(); i += 3) junk[i] = std::numeric_limits<float>::infinity();
  bad = in;
  bad.scan.ranges = junk.data();
  const auto& r = localiser.Update(bad);
  EXPECT_EQ(r.rejection, nullptr);
  EXPECT_EQ(r.prefilter.non_finite, 300u);
  EXPECT_TRUE(r.lost);
  EXPECT_EQ(r.lost_reason, LostReason::kNoFeatures);
  EXPECT_TRUE(geometry::IsFinite(r.pose));
  // Good data afterwards still localises.
  const auto& good = localiser.Update(in);
  EXPECT_FALSE(good.lost) << ToString(good.lost_reason);
  EXPECT_NEAR(good.pose.x, truth_.x, 1e-3);
}

TEST_F(LocaliserFixture, ATooLargeCorrectionIsRefusedAndOdometryKept) {
  LocaliserOptions o;
  o.max_correction_m = 0.01;
  Localiser localiser(world_, o);
  std::mt19937 rng(3);
  auto scan = testing::CastScan(scene_, truth_, {}, rng);
  UpdateInput in;
  in.scan = scan.View();
  in.odometry_pose = {1.05, 0.86, 0.01};
  in.odometry_covariance = Eigen::Vector3d(0.01, 0.01, 0.01).asDiagonal();
  const auto& r = localiser.Update(in);
  EXPECT_TRUE(r.lost);
  EXPECT_EQ(r.lost_reason, LostReason::kCorrectionTooLarge);
  EXPECT_DOUBLE_EQ(r.pose.x, 1.05);
}

// A scan taken while moving at 1 m/s and turning at 90 deg/s over 0.1 s:
// every beam from its own pose.
TEST_F(LocaliserFixture, DeskewingRemovesTheSkewOfAScanTakenWhileMoving) {
  const int beams = 300;
  const double scan_time = 0.1, v = 1.0, w = kPi / 2;
  const double inc = 2 * kPi / beams;
  std::vector<float> ranges(beams);
  BeamMotion motion;
  motion.Resize(beams);
  for (int i = 0; i < beams; ++i) {
    const double t = scan_time * i / beams;
    const Pose2D rel{v * t, 0.0,
                     w * t};  // approximately straight at this scale; exact for the test
    const Pose2D p = geometry::Compose(truth_, rel);
    const double a = p.theta - kPi + i * inc;
    ranges[static_cast<size_t>(i)] =
        static_cast<float>(scene_.Cast(p.Translation(), {std::cos(a), std::sin(a)}, 30.0));
    motion.x[static_cast<size_t>(i)] = rel.x;
    motion.y[static_cast<size_t>(i)] = rel.y;
    motion.c[static_cast<size_t>(i)] = std::cos(rel.theta);
    motion.s[static_cast<size_t>(i)] = std::sin(rel.theta);
  }
  ScanView view;
  view.ranges = ranges.data();
  view.count = ranges.size();
  view.angle_min = -kPi;
  view.angle_increment = inc;
  view.range_max = 30.0;
  UpdateInput in;
  in.scan = view;
  in.odometry_pose = {1.02, 0.89, 0.001};
  in.odometry_covariance = Eigen::Vector3d(0.01, 0.01, 0.01).asDiagonal();
  Localiser skewed(world_, LocaliserOptions{});
  const Pose2D raw = skewed.Update(in).pose;
  Localiser deskewed(world_, LocaliserOptions{});
  in.motion = &motion;
  const auto& fixed = deskewed.Update(in);
  EXPECT_FALSE(fixed.lost) << ToString(fixed.lost_reason);
  const double err_fixed = std::hypot(fixed.pose.x - truth_.x, fixed.pose.y - truth_.y);
  const double err_raw = std::hypot(raw.x - truth_.x, raw.y - truth_.y);
  EXPECT_LT(err_fixed, 1e-3);
  EXPECT_LT(std::abs(fixed.pose.theta - truth_.theta), 1e-3);
  EXPECT_GT(err_raw + std::abs(raw.theta - truth_.theta), 10 * err_fixed);
}

TEST_F(LocaliserFixture, KohonenStrategyMatchesTheSameWallsDeterministically) {
  LocaliserOptions o;
  o.kinds.Get<WallKindOptions>().strategy = WallStrategy::kKohonen;
  std::mt19937 rng(11);
  auto scan = testing::CastScan(scene_, truth_, {300, 2 * kPi, 30.0, 0.005}, rng);
  UpdateInput in;
  in.scan = scan.View();
  in.odometry_pose = {1.02, 0.89, 0.001};
  in.odometry_covariance = Eigen::Vector3d(0.01, 0.01, 0.01).asDiagonal();
  Localiser a(world_, o), b(world_, o);
  const auto ra = a.Update(in);
  const auto rb = b.Update(in);
  EXPECT_EQ(ra.Kind("walls")->Matched(), 3);
  EXPECT_DOUBLE_EQ(ra.pose.x, rb.pose.x);
  EXPECT_DOUBLE_EQ(ra.pose.y, rb.pose.y);
  EXPECT_NEAR(ra.pose.x, truth_.x, 0.01);
  EXPECT_NEAR(ra.pose.y, truth_.y, 0.01);
}

}  // namespace
}  // namespace structloc::localisation_core
