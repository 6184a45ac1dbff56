// Regression tests for the bad-input review of 12de806 (localisation defects):
// each test is named after the defect it keeps fixed (H = high, M = medium,
// L = low). The tracker-level tests run the core directly; the others run the
// real structloc_localisation process against a feeder over DDS.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "localisation_feed.hpp"
#include "pose_argument.hpp"
#include "structloc/localisation_core/tracking/pose_tracker.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
using localisation_core::PoseTracker;
using localisation_core::Rejection;

constexpr int kDomain = testing::domains::kBadInputLocalisation;

Eigen::Matrix3d DiagonalCovariance() {
  return Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal();
}

// A tracker on the office map; Start() gives it odometry and a pose at t = 1 s.
struct TrackerFixture {
  world_model::WorldModel world =
      world_model::LoadWorldModel(testing::SourcePath("maps/office_floor.xml"));
  localisation_core::LocaliserOptions options =
      localisation_core::LoadLocaliserOptions(testing::SourcePath("maps/params/office_sick.xml"));
  PoseTracker tracker{world, options, localisation_core::TrackerOptions{}};
  std::vector<float> ranges;

  void Start() {
    ASSERT_FALSE(tracker.AddOdometry(1.0, {2, 6.5, 0}).has_value());
    ASSERT_FALSE(tracker.SetInitialPose(1.0, {2, 6.5, 0}, DiagonalCovariance()).has_value());
  }
  // A 180 deg scan at t = 1 s of `beams` 5 m readings.
  PoseTracker::ScanOutcome Scan(size_t beams, double time_increment) {
    ranges.assign(beams, 5.0f);
    localisation_core::ScanInput scan;
    scan.stamp = 1.0;
    scan.angle_min = -1.57;
    scan.angle_increment = 3.14 / static_cast<double>(beams - 1);
    scan.angle_max = scan.angle_min + static_cast<double>(beams - 1) * scan.angle_increment;
    scan.time_increment = time_increment;
    scan.range_max = 30;
    scan.ranges = ranges.data();
    scan.count = ranges.size();
    return tracker.ProcessScan(scan, 0.0);
  }
};

process::ChildProcess StartLocalisation(std::vector<std::string> extra, int domain = kDomain) {
  std::vector<std::string> args = {"--domain", std::to_string(domain),
                                   "--qos",    testing::ShippedQos(),
                                   "--params", testing::SimulatedRobotParams()};
  args.insert(args.end(), extra.begin(), extra.end());
  return process::ChildProcess(std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation", args);
}

simulation_core::Scenario Office(double seconds) {
  auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  scenario.duration_s = seconds;
  return scenario;
}

// --- tracker level --------------------------------------------------------

TEST(BadInputLocalisation, H4_InitialPoseCovarianceMustBePositiveDefinite) {
  TrackerFixture f;
  ASSERT_FALSE(f.tracker.AddOdometry(1.0, {0, 0, 0}).has_value());
  Eigen::Matrix3d not_pd = Eigen::Vector3d(1e-6, 1e-6, 1e-6).asDiagonal();
  not_pd(0, 1) = not_pd(1, 0) = 1.0;  // positive diagonal, indefinite
  EXPECT_EQ(f.tracker.SetInitialPose(1.0, {2, 6.5, 0}, not_pd), Rejection::kInitialPoseInvalid);
  Eigen::Matrix3d asymmetric = DiagonalCovariance();
  asymmetric(0, 2) = 0.005;
  EXPECT_EQ(f.tracker.SetInitialPose(1.0, {2, 6.5, 0}, asymmetric), Rejection::kInitialPoseInvalid);
  EXPECT_FALSE(f.tracker.HasInitialPose());
  EXPECT_FALSE(f.tracker.SetInitialPose(1.0, {2, 6.5, 0}, DiagonalCovariance()).has_value());
  EXPECT_TRUE(f.tracker.HasInitialPose());
  EXPECT_NE(std::string(localisation_core::ToString(Rejection::kInitialPoseInvalid))
                .find("symmetric positive definite"),
            std::string::npos);
}

TEST(BadInputLocalisation, M1_OdometryWithoutAUnitQuaternionOrWithAHeadingJumpIsRejected) {
  geometry_msgs::msg::Quaternion zero;
  zero.w(0.0);
  EXPECT_TRUE(std::isnan(dds_common::YawFromQuaternion(zero)));
  auto scaled = dds_common::ToQuaternion(0.7);
  scaled.z(scaled.z() * 3);
  scaled.w(scaled.w() * 0.2);
  EXPECT_TRUE(std::isnan(dds_common::YawFromQuaternion(scaled)));
  EXPECT_NEAR(dds_common::YawFromQuaternion(dds_common::ToQuaternion(0.7)), 0.7, 1e-12);

  TrackerFixture f;
  ASSERT_FALSE(f.tracker.AddOdometry(1.0, {0, 0, 1.5}).has_value());
  EXPECT_EQ(f.tracker.AddOdometry(1.02, {0, 0, std::nan("")}), Rejection::kOdometryNonFinite);
  // Yaw 1.5 -> 0 in 20 ms: what an all-zero quaternion read as yaw 0 looked like.
  EXPECT_EQ(f.tracker.AddOdometry(1.04, {0.001, 0, 0.0}), Rejection::kOdometryJump);
  EXPECT_FALSE(f.tracker.AddOdometry(1.06, {0.002, 0, 1.52}).has_value());
}

TEST(BadInputLocalisation, M11_ScanWithAnAbsurdTimeIncrementIsRejected) {
  TrackerFixture f;
  f.Start();
  const auto outcome = f.Scan(361, 1e30);
  EXPECT_EQ(outcome.verdict, PoseTracker::ScanVerdict::kRejected);
  EXPECT_EQ(outcome.rejection, Rejection::kScanTooLong);
}

TEST(BadInputLocalisation, M7_LocaliserRejectionsAreCountedWithTheirReason) {
  TrackerFixture f;
  f.Start();
  const auto outcome = f.Scan(static_cast<size_t>(f.options.max_beams) + 1, 0.0);
  EXPECT_EQ(outcome.verdict, PoseTracker::ScanVerdict::kRejected);
  EXPECT_EQ(outcome.rejection, Rejection::kTooManyBeams);
  EXPECT_EQ(f.tracker.Stats().scans_lost, 0u);
  EXPECT_EQ(f.tracker.Stats().Rejected(), 1u);
}

// --- the component over DDS -----------------------------------------------

TEST(BadInputLocalisation, H4_M1_M11_HostileSamplesAreRejectedWithReasonsAndTrackingHolds) {
  const auto scenario = Office(10.0);
  testing::LocalisationFeed feed("hostile_feeder", kDomain);
  auto localisation =
      StartLocalisation({"--initial-pose", testing::PoseArgument(scenario.initial_pose)});
  ASSERT_TRUE(feed.WaitForLocalisation(testing::kGenerousTimeout)) << localisation.CapturedOutput();
  size_t good_sent = 0;
  feed.Play(scenario,
            [&](int k, const simulation_core::SimState& s, sensor_msgs::msg::LaserScan& scan) {
              if (k == 30) {
                // H4: a wrong pose with a positive diagonal that is not positive definite.
                geometry_msgs::msg::PoseWithCovarianceStamped bad;
                bad.header().stamp(scan.header().stamp());
                bad.header().frame_id("map");
                bad.pose().pose().position().x(s.truth.x + 0.3);
                bad.pose().pose().position().y(s.truth.y);
                bad.pose().pose().orientation(dds_common::ToQuaternion(s.truth.theta));
                bad.pose().covariance()[0] = bad.pose().covariance()[7] = 1e-6;
                bad.pose().covariance()[35] = 1e-6;
                bad.pose().covariance()[1] = bad.pose().covariance()[6] = 1.0;
                feed.InitialPoseWriter().Write(bad);
              }
              if (k % 5 == 0) {
                // M1: an uninitialised orientation on every fifth odometry sample.
                auto odom = simulator::ToOdometry(s, 0.0, testing::LocalisationFeed::kClockOffset);
                odom.header().stamp(
                    dds_common::ToRosTime(dds_common::FromRosTime(odom.header().stamp()) + 0.001));
                odom.pose().pose().orientation(geometry_msgs::msg::Quaternion());
                odom.pose().pose().orientation().w(0.0);
                feed.OdometryWriter().Write(odom);
              }
              if (k % 7 == 0) {
                scan.time_increment(1e30f);  // M11
              } else {
                ++good_sent;
              }
              return true;
            });
  const auto headline_while_fed = feed.Headline().second;
  // The rejections show in the diagnostics, published about once a second.
  const std::vector<std::string> reasons = {
      "rejected: initial pose not finite or its covariance not symmetric positive definite",
      "rejected: odometry pose or stamp not finite, or its orientation not a unit quaternion",
      "rejected: time_increment x beams longer than max_scan_duration_s"};
  // The good scans the component took gave poses (a few may be lost on the
  // way, or dropped for the newest when the test machine is loaded).
  EXPECT_TRUE(testing::WaitUntil([&] {
    return feed.Answered() > good_sent * 4 / 5 &&
           std::all_of(reasons.begin(), reasons.end(),
                       [&](const auto& r) { return !feed.Value(r).empty(); });
  })) << localisation.CapturedOutput();
  EXPECT_FALSE(localisation.Poll().has_value()) << localisation.CapturedOutput();
  EXPECT_FALSE(feed.NonFinitePoseSeen());
  EXPECT_GT(feed.Answered(), good_sent * 4 / 5);
  EXPECT_GT(feed.Poses(), good_sent / 2);
  EXPECT_LT(feed.WorstError(), 0.015);
  for (const auto& reason : reasons) EXPECT_NE(feed.Value(reason), "") << reason;
  EXPECT_EQ(headline_while_fed, "localised");
}

TEST(BadInputLocalisation, M7_DiagnosticsNameTheMissingSourceAndEscalate) {
  testing::LocalisationFeed feed("silent_feeder", kDomain);
  auto localisation = StartLocalisation({"--initial-pose", "2 6.5 0"});
  ASSERT_TRUE(feed.WaitForLocalisation(testing::kGenerousTimeout)) << localisation.CapturedOutput();
  // An initial pose was given, but no odometry arrives: say that, not "no initial pose".
  ASSERT_TRUE(testing::WaitUntil([&] { return feed.Headline().first == 1; }));
  EXPECT_NE(feed.Headline().second.find("no odometry on rt/odom yet"), std::string::npos)
      << feed.Headline().second;
  // Silent for longer than 5 s: an error, with the elapsed time.
  ASSERT_TRUE(testing::WaitUntil([&] { return feed.Headline().first == 2; }))
      << feed.Headline().second;
  EXPECT_NE(feed.Headline().second.find("no odometry on rt/odom yet for "), std::string::npos);
  EXPECT_NE(localisation.CapturedOutput().find("ERROR no odometry on rt/odom yet"),
            std::string::npos)
      << localisation.CapturedOutput();
}

TEST(BadInputLocalisation, M7_IncompatibleQosIsReported) {
  testing::LocalisationFeed feed("qos_feeder", kDomain);
  // A reader that wants TRANSIENT_LOCAL durability from the VOLATILE pose writer.
  const auto durable_reader =
      feed.Node().Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
          {"rt/pose", "latched_result"},
          [](const geometry_msgs::msg::PoseWithCovarianceStamped&) {});
  auto localisation = StartLocalisation({"--initial-pose", "2 6.5 0"});
  ASSERT_TRUE(feed.WaitForLocalisation(testing::kGenerousTimeout)) << localisation.CapturedOutput();
  ASSERT_TRUE(testing::WaitUntil([&] {
    return feed.AnyMessageContains("incompatible DURABILITY QoS");
  })) << localisation.CapturedOutput();
  EXPECT_EQ(feed.Headline().first, 2);
  EXPECT_NE(localisation.CapturedOutput().find("publication on rt/pose cannot match a peer"),
            std::string::npos)
      << localisation.CapturedOutput();
}

TEST(BadInputLocalisation, M8_TwoInstancesOnOneDomainAreDetected) {
  testing::LocalisationFeed feed("duplicate_watcher", kDomain);
  auto first = StartLocalisation({});
  auto second = StartLocalisation({});
  ASSERT_TRUE(testing::WaitUntil([&] {
    return first.CapturedOutput().find("another participant named 'localisation'") !=
               std::string::npos &&
           second.CapturedOutput().find("another participant named 'localisation'") !=
               std::string::npos;
  })) << first.CapturedOutput()
      << second.CapturedOutput();
  ASSERT_TRUE(testing::WaitUntil(
      [&] { return feed.AnyMessageContains("two instances of this component"); }));
  EXPECT_EQ(feed.Headline().first, 2);
}

TEST(BadInputLocalisation, M10_UnusableStateFileIsIgnoredAndTheComponentStarts) {
  testing::TempDir dir;
  std::filesystem::create_directory(dir / "a_folder");
  for (const auto& state :
       {dir.Write("empty.txt", ""), dir.Write("nan.txt", "map_to_odom nan 1 2 3 4 5\n"),
        dir / "a_folder"}) {
    auto localisation = StartLocalisation({"--state-file", state}, kDomain);
    ASSERT_TRUE(testing::WaitUntil([&] {
      return localisation.CapturedOutput().find("running") != std::string::npos;
    })) << localisation.CapturedOutput();
    EXPECT_NE(localisation.CapturedOutput().find("ignoring the saved pose: " + state),
              std::string::npos)
        << localisation.CapturedOutput();
    EXPECT_FALSE(localisation.Poll().has_value()) << localisation.CapturedOutput();
    EXPECT_EQ(localisation.Stop(testing::kGenerousTimeout), 0);
  }
}

}  // namespace
}  // namespace structloc
