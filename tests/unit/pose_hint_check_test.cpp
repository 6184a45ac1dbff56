// PoseHintCheck (pose_hint_check.hpp): a hint's map -> odom correction that
// is off (a saved one that drifted while the localisation was down, an
// initial pose held for odometry that came late) is confirmed and mended by
// a local search around the pose it predicts (the prediction breaking a tie
// between two equally good poses); a scan that confirms nothing is tried
// again, and after the attempts allowed the check gives up (the caller then
// starts from the hint unconfirmed).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "initial_pose_expectations.hpp"
#include "office_scene.hpp"
#include "structloc/localisation_core/global/pose_hint_check.hpp"

namespace structloc::localisation_core {
namespace {

// The correction that puts the robot at `robot` for the odometry pose `odom`,
// turned by `turn` and shifted by (dx, dy): a saved correction gone stale.
SessionState Stale(const geometry::Pose2D& robot, const geometry::Pose2D& odom, double dx,
                   double dy, double turn) {
  const geometry::Pose2D exact = geometry::Compose(robot, geometry::Inverse(odom));
  return {geometry::Pose2D{exact.x + dx, exact.y + dy, exact.theta + turn},
          Eigen::Vector3d(1e-6, 1e-6, 1e-7)};
}

TEST(PoseHintCheck, MendsACorrectionThatDriftedWhileTheLocalisationWasDown) {
  const testing::OfficeScene office(4.71238898038469);
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.0025, 0.0025, 0.0009).asDiagonal();
  const GlobalStart search(office.world, office.options.sensor_mount, covariance);
  const geometry::Pose2D odom{3.0, -1.0, 0.4};
  // 0.4 m and 0.06 rad off: far outside the tracker's gates under the
  // variance the correction was saved with, well inside the search.
  PoseHintCheck check(Stale(office.truth, odom, 0.3, -0.25, 0.06), "a stale correction", {});
  std::mt19937 rng(3);
  const auto outcome =
      check.Check(search, testing::SessionScanOf(office.Scan(1081, rng), 7.0), odom);
  ASSERT_EQ(outcome.verdict, PoseHintCheck::Verdict::kFound) << outcome.result.reason;
  EXPECT_GT(std::hypot(outcome.predicted.x - office.truth.x, outcome.predicted.y - office.truth.y),
            0.1);
  ASSERT_TRUE(outcome.found);
  testing::ExpectFoundAt(*outcome.found, 7.0, office.truth, covariance);
}

// The demo's start, given on the command line, but the first odometry
// reached the localisation only when the robot had driven 0.9 m along the
// corridor (readers matched late on a lossy network): a tracker started
// there kept the 0.9 m (its gates refuse every pairing that would mend it).
TEST(PoseHintCheck, MendsAnInitialPoseHeldForOdometryThatCameLate) {
  testing::OfficeScene office(4.71238898038469);
  office.truth = {2.9, 6.5, 0.0};
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.0025, 0.0025, 0.0009).asDiagonal();
  const GlobalStart search(office.world, office.options.sensor_mount, covariance);
  // The odometry had counted 0.9 m when its first sample arrived, and the
  // given pose was taken for that sample.
  const geometry::Pose2D first_odometry{0.9, 0.0, 0.0};
  const geometry::Pose2D given{2.0, 6.5, 0.0};
  PoseHintCheck check(
      {geometry::Compose(given, geometry::Inverse(first_odometry)), covariance.diagonal()},
      "the initial pose", {});
  std::mt19937 rng(5);
  const auto outcome =
      check.Check(search, testing::SessionScanOf(office.Scan(1081, rng), 2.0), first_odometry);
  EXPECT_NEAR(outcome.predicted.x, 2.0, 1e-9);
  ASSERT_EQ(outcome.verdict, PoseHintCheck::Verdict::kFound) << outcome.result.reason;
  testing::ExpectFoundAt(*outcome.found, 2.0, office.truth, covariance);
}

TEST(PoseHintCheck, LooksOnlyNearThePredictedPose) {
  const testing::OfficeScene office(4.71238898038469);
  const GlobalStart search(office.world, office.options.sensor_mount, Eigen::Matrix3d::Identity());
  const geometry::Pose2D odom{0.0, 0.0, 0.0};
  PoseHintCheckOptions options;
  options.attempts = 2;
  // The correction puts the robot 4 m from where it is: nothing near there
  // explains the scan, so nothing is confirmed, and after two scans it gives up.
  PoseHintCheck check(Stale(office.truth, odom, 3.0, -3.0, 0.0), "a far correction", options);
  std::mt19937 rng(4);
  const auto first = check.Check(search, testing::SessionScanOf(office.Scan(1081, rng), 1.0), odom);
  EXPECT_NE(first.verdict, PoseHintCheck::Verdict::kFound);
  if (first.found) {
    EXPECT_GT(
        std::hypot(first.found->pose.x - office.truth.x, first.found->pose.y - office.truth.y),
        1.0);
  }
  EXPECT_EQ(first.verdict, PoseHintCheck::Verdict::kTryAgain);
  const auto second =
      check.Check(search, testing::SessionScanOf(office.Scan(1081, rng), 1.1), odom);
  EXPECT_EQ(second.verdict, PoseHintCheck::Verdict::kGiveUp);
}

// An operator's pose 40 deg and 0.3 m off, with RViz's default covariance
// (0.5 m and 15 deg of standard deviation): the window spans 3 sigma of it
// (45 deg) and mends it. The same pose sent as if it were exact is searched
// only in the default 30 deg, finds nothing there, and is tried again.
TEST(PoseHintCheck, SearchesAsWideAsTheHintsOwnUncertainty) {
  const testing::OfficeScene office(4.71238898038469);
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.0025, 0.0025, 0.0009).asDiagonal();
  const GlobalStart search(office.world, office.options.sensor_mount, covariance);
  // No odometry travel: turning the correction turns the predicted pose in place.
  const geometry::Pose2D odom{0.0, 0.0, 0.4};
  SessionState operators = Stale(office.truth, odom, 0.2, -0.2, 0.7);
  std::mt19937 rng(6);
  const auto scan = testing::SessionScanOf(office.Scan(1081, rng), 3.0);

  PoseHintCheck exact(operators, "a pose sent as exact", {});
  const auto narrow = exact.Check(search, scan, odom);
  EXPECT_NEAR(exact.HeadingRad(), PoseHintCheckOptions{}.heading_rad, 1e-12);
  EXPECT_NEAR(exact.RadiusM(), PoseHintCheckOptions{}.radius_m, 1e-12);
  EXPECT_EQ(narrow.verdict, PoseHintCheck::Verdict::kTryAgain) << narrow.result.reason;

  operators.variance = Eigen::Vector3d(0.25, 0.25, 0.06853891945200942);
  PoseHintCheck clicked(operators, "an operator's pose", {});
  const auto wide = clicked.Check(search, scan, odom);
  EXPECT_NEAR(clicked.HeadingRad(), 3.0 * std::sqrt(0.06853891945200942), 1e-9);
  EXPECT_NEAR(clicked.RadiusM(), PoseHintCheckOptions{}.radius_m, 1e-12);  // 1.5 m < 2 m
  ASSERT_EQ(wide.verdict, PoseHintCheck::Verdict::kFound) << wide.result.reason;
  testing::ExpectFoundAt(*wide.found, 3.0, office.truth, covariance);
}

// "I have no idea" (a huge or infinite variance) is searched only as far as
// max_radius_m and half a turn: wider is the global localiser's job.
TEST(PoseHintCheck, AWindowFromAVagueHintStaysBounded) {
  const PoseHintCheck check({{}, Eigen::Vector3d(1e6, INFINITY, 1e6)}, "a vague pose", {});
  EXPECT_DOUBLE_EQ(check.RadiusM(), PoseHintCheckOptions{}.max_radius_m);
  EXPECT_DOUBLE_EQ(check.HeadingRad(), geometry::kPi);
}

// Two poses explaining the scan equally well (along a corridor): the one near
// the pose the saved correction predicts is taken, none when neither is near.
TEST(PoseHintCheck, ThePredictionBreaksATieAsATrackersPriorWould) {
  const testing::OfficeScene office(4.71238898038469);
  const GlobalStart search(office.world, office.options.sensor_mount, Eigen::Matrix3d::Identity());
  const geometry::Pose2D mount = office.options.sensor_mount;
  GlobalResult tie;
  tie.decision = GlobalDecision::kAmbiguous;
  tie.best =
      GlobalCandidate{geometry::Compose(geometry::Pose2D{5.0, 6.5, 0.0}, mount), 0.8, std::nullopt};
  tie.runner_up = GlobalCandidate{geometry::Compose(geometry::Pose2D{7.0, 6.5, 0.0}, mount), 0.78,
                                  std::nullopt};
  SessionScan scan;
  scan.geometry.stamp = 4.0;
  const auto near_runner_up = search.NearestOfTie(scan, tie, {6.9, 6.45, 0.05}, 0.3, 0.1);
  ASSERT_TRUE(near_runner_up);
  EXPECT_DOUBLE_EQ(near_runner_up->stamp, 4.0);
  EXPECT_NEAR(near_runner_up->pose.x, 7.0, 1e-9);
  EXPECT_NEAR(near_runner_up->pose.y, 6.5, 1e-9);
  EXPECT_FALSE(search.NearestOfTie(scan, tie, {6.0, 6.5, 0.0}, 0.3, 0.1));
  EXPECT_FALSE(search.NearestOfTie(scan, tie, {5.0, 6.5, 0.3}, 0.3, 0.1));
}

TEST(PoseHintCheck, RefusesOptionsThatSearchNothing) {
  PoseHintCheckOptions options;
  options.radius_m = 0.0;
  EXPECT_THROW(PoseHintCheck({}, "nothing", options), std::invalid_argument);
  options = {};
  options.attempts = 0;
  EXPECT_THROW(PoseHintCheck({}, "nothing", options), std::invalid_argument);
  options = {};
  options.max_radius_m = options.radius_m / 2;
  EXPECT_THROW(PoseHintCheck({}, "nothing", options), std::invalid_argument);
  options = {};
  options.sigmas = NAN;
  EXPECT_THROW(PoseHintCheck({}, "nothing", options), std::invalid_argument);
}

}  // namespace
}  // namespace structloc::localisation_core
