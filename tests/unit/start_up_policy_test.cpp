// StartUpPolicy (start_up_policy.hpp), without DDS: a robot without a pose is
// located on the whole map; a pose given live, or a saved correction, is a
// hint confirmed by a local search before the tracking trusts it, while a
// log's initial pose is taken as it is; one search is out at a time, and an
// answer made outdated by a pose given or a relocalisation asked for
// meanwhile changes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "office_scene.hpp"
#include "structloc/localisation_core/start_up/start_up_policy.hpp"

namespace structloc::localisation_core {
namespace {

using Kind = StartUpSearch::Kind;
constexpr double kFieldOfView = 4.71238898038469;
constexpr double kScanStamp = 10.0;

// The office hall, a live session, and the robot standing still at the
// hall's true pose with its odometry at the origin.
struct Rig {
  testing::OfficeScene office{kFieldOfView};
  SessionOptions session_options;
  TrackingSession session{&office.world, office.options, session_options, Scheduling::kNewestWins};
  std::mt19937 rng{7};

  explicit Rig(bool confirm_given_poses = true) {
    StartUpOptions options;
    options.confirm_given_poses = confirm_given_poses;
    policy = std::make_unique<StartUpPolicy>(&office.world, office.options.sensor_mount,
                                             session_options, options);
  }
  std::unique_ptr<StartUpPolicy> policy;

  void Odometry() {
    for (double t = kScanStamp - 0.2; t <= kScanStamp + 0.21; t += 0.1)
      session.AddOdometry(t, {}, t);
  }
  SessionScan Scan() { return testing::SessionScanOf(office.Scan(1081, rng), kScanStamp); }
  // The robot pose the session tracks (through its map -> odom correction).
  geometry::Pose2D Tracked() const { return session.Tracker()->MapToOdom(); }
};

void ExpectNear(const geometry::Pose2D& pose, const geometry::Pose2D& truth) {
  EXPECT_NEAR(pose.x, truth.x, 0.05);
  EXPECT_NEAR(pose.y, truth.y, 0.05);
  EXPECT_NEAR(pose.theta, truth.theta, 0.03);
}

TEST(StartUpPolicy, WithoutAPoseTheWholeMapIsSearchedAndItsPoseTracked) {
  Rig rig;
  rig.Odometry();
  EXPECT_EQ(rig.policy->State(rig.session), "searching the map");
  auto search = rig.policy->SearchAt(rig.session, rig.Scan());
  ASSERT_TRUE(search);
  EXPECT_EQ(search->kind, Kind::kGlobal);
  rig.policy->Run(*search);
  const auto outcome = rig.policy->Apply(rig.session, *search, kScanStamp);
  EXPECT_FALSE(outcome.outdated);
  ASSERT_TRUE(outcome.pose_set) << search->global->result.reason;
  EXPECT_FALSE(rig.session.WaitingForInitialPose());
  ExpectNear(rig.Tracked(), rig.office.truth);
  EXPECT_EQ(rig.policy->State(rig.session), "tracking");
  EXPECT_FALSE(rig.policy->SearchAt(rig.session, rig.Scan())) << "a tracked robot is not searched";
}

TEST(StartUpPolicy, OneSearchIsOutAtATime) {
  Rig rig;
  rig.Odometry();
  auto first = rig.policy->SearchAt(rig.session, rig.Scan());
  ASSERT_TRUE(first);
  EXPECT_TRUE(rig.policy->SearchUnderway());
  EXPECT_FALSE(rig.policy->SearchAt(rig.session, rig.Scan()));
  rig.policy->Run(*first);
  rig.policy->Apply(rig.session, *first, kScanStamp);
  EXPECT_FALSE(rig.policy->SearchUnderway());
}

TEST(StartUpPolicy, AnAnswerOutdatedByAPoseGivenMeanwhileChangesNothing) {
  Rig rig;
  rig.Odometry();
  auto search = rig.policy->SearchAt(rig.session, rig.Scan());
  ASSERT_TRUE(search);
  // An operator's pose arrives while the search runs, 1 m from the truth.
  const geometry::Pose2D given{rig.office.truth.x + 1.0, rig.office.truth.y,
                               rig.office.truth.theta};
  ASSERT_EQ(rig.session.SetInitialPose(
                {kScanStamp, given, rig.session_options.tracker.InitialCovariance()},
                "rt/initialpose", kScanStamp),
            TrackingSession::InitialPoseOutcome::kSet);
  rig.policy->GivenOnTopic(rig.session, "rt/initialpose");
  rig.policy->Run(*search);
  const auto outcome = rig.policy->Apply(rig.session, *search, kScanStamp);
  EXPECT_TRUE(outcome.outdated);
  EXPECT_FALSE(outcome.pose_set);
  EXPECT_NEAR(rig.Tracked().x, given.x, 1e-9);
}

TEST(StartUpPolicy, AGivenPoseIsAHintConfirmedByALocalSearchBeforeItIsTracked) {
  Rig rig;
  // Given 0.4 m and 3 deg off (an operator's click).
  const geometry::Pose2D given{rig.office.truth.x - 0.4, rig.office.truth.y + 0.1,
                               rig.office.truth.theta + 0.05};
  rig.policy->GivenAtStart(rig.session, given, TrackingSession::InitialPoseWhen::kAtFirstOdometry,
                           "the given pose");
  rig.Odometry();
  ASSERT_TRUE(rig.session.HasInitialPose());
  rig.policy->Tend(rig.session);
  EXPECT_TRUE(rig.session.WaitingForInitialPose()) << "taken back as a hint";
  EXPECT_EQ(rig.policy->State(rig.session), "confirming the given pose");
  auto search = rig.policy->SearchAt(rig.session, rig.Scan());
  ASSERT_TRUE(search);
  EXPECT_EQ(search->kind, Kind::kHint);
  rig.policy->Run(*search);
  const auto outcome = rig.policy->Apply(rig.session, *search, kScanStamp);
  ASSERT_TRUE(outcome.pose_set);
  ASSERT_EQ(outcome.log.size(), 1u);
  EXPECT_NE(outcome.log[0].find("the given pose confirmed by a local search"), std::string::npos)
      << outcome.log[0];
  ExpectNear(rig.Tracked(), rig.office.truth);
}

TEST(StartUpPolicy, ALogsInitialPoseIsTakenAsItIs) {
  Rig rig(/*confirm_given_poses=*/false);
  const geometry::Pose2D given{rig.office.truth.x - 0.4, rig.office.truth.y,
                               rig.office.truth.theta};
  rig.policy->GivenAtStart(rig.session, given, TrackingSession::InitialPoseWhen::kAtFirstOdometry,
                           "--initial-pose");
  rig.Odometry();
  rig.policy->Tend(rig.session);
  EXPECT_FALSE(rig.session.WaitingForInitialPose());
  EXPECT_FALSE(rig.policy->SearchAt(rig.session, rig.Scan()));
  EXPECT_NEAR(rig.Tracked().x, given.x, 1e-9);
}

TEST(StartUpPolicy, ASavedCorrectionIsConfirmedBeforeTheTrackingTrustsIt) {
  Rig rig;
  // Saved 0.3 m off: the odometry ran on while the localisation was down.
  const SessionState saved{
      {rig.office.truth.x + 0.3, rig.office.truth.y - 0.2, rig.office.truth.theta},
      Eigen::Vector3d(1e-6, 1e-6, 1e-7)};
  EXPECT_EQ(rig.policy->Resume(rig.session, saved, "the pose saved in F"),
            "resuming from the pose saved in F once a search around it confirms it");
  rig.Odometry();
  EXPECT_TRUE(rig.session.WaitingForInitialPose());
  auto search = rig.policy->SearchAt(rig.session, rig.Scan());
  ASSERT_TRUE(search);
  EXPECT_EQ(search->kind, Kind::kHint);
  rig.policy->Run(*search);
  ASSERT_TRUE(rig.policy->Apply(rig.session, *search, kScanStamp).pose_set);
  ExpectNear(rig.Tracked(), rig.office.truth);
}

TEST(StartUpPolicy, ARelocalisationForgetsThePoseAndSearchesAgain) {
  Rig rig(/*confirm_given_poses=*/false);
  rig.policy->GivenAtStart(rig.session, rig.office.truth,
                           TrackingSession::InitialPoseWhen::kAtFirstOdometry, "--initial-pose");
  rig.Odometry();
  ASSERT_FALSE(rig.session.WaitingForInitialPose());
  const auto sentence = rig.policy->Relocalise(rig.session, "rt/reinitialize_global_localization");
  ASSERT_TRUE(sentence);
  EXPECT_EQ(*sentence, "relocalising globally, as asked on rt/reinitialize_global_localization");
  EXPECT_TRUE(rig.session.WaitingForInitialPose());
  auto search = rig.policy->SearchAt(rig.session, rig.Scan());
  ASSERT_TRUE(search);
  EXPECT_EQ(search->kind, Kind::kGlobal);
}

TEST(StartUpPolicy, WithoutAMapNothingIsSearchedAndAGivenPoseIsTaken) {
  testing::OfficeScene office(kFieldOfView);
  const SessionOptions session_options;
  TrackingSession session(&office.world, office.options, session_options, Scheduling::kNewestWins);
  StartUpPolicy policy(nullptr, office.options.sensor_mount, session_options, {});
  EXPECT_FALSE(policy.CanSearch());
  EXPECT_EQ(policy.State(session), "waiting for an initial pose");
  EXPECT_FALSE(policy.Relocalise(session, "rt/reinitialize_global_localization"));
  policy.GivenAtStart(session, office.truth, TrackingSession::InitialPoseWhen::kAtFirstOdometry,
                      "the given pose");
  session.AddOdometry(1.0, {}, 1.0);
  policy.Tend(session);
  EXPECT_FALSE(session.WaitingForInitialPose()) << "nothing to confirm it with";
}

}  // namespace
}  // namespace structloc::localisation_core
