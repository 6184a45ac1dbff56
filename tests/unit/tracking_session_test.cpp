// The tracking session without any middleware: scheduling (newest wins live,
// in order offline), the initial-pose / saved-correction state machine,
// lost timers, when the pose is due to be saved, rejection reasons, and the
// <tracking> block of the parameter files.
#include <gtest/gtest.h>

#include <random>

#include "office_scene.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/localisation_core/tracking/tracking_session.hpp"
#include "temp_dir.hpp"
#include "whole_params.hpp"

namespace structloc::localisation_core {
namespace {

const std::string kParams = std::string(STRUCTLOC_SOURCE_DIR) + "/maps/params/office_sick.xml";

// A scan of the office hall seen from the scene's true pose, stamped `stamp`.
SessionScan HallScan(const testing::OfficeScene& office, double stamp, std::mt19937& rng) {
  const auto synthetic = office.Scan(1081, rng);
  SessionScan scan;
  scan.geometry.stamp = stamp;
  scan.geometry.angle_min = synthetic.angle_min;
  scan.geometry.angle_increment = synthetic.angle_increment;
  scan.geometry.angle_max =
      synthetic.angle_min + synthetic.angle_increment * (synthetic.ranges.size() - 1);
  scan.geometry.range_max = synthetic.max_range_m;
  scan.ranges = synthetic.ranges;
  return scan;
}

// A scan that sees nothing of the map: every beam at its maximum range.
SessionScan EmptyRoomScan(double stamp) {
  SessionScan scan;
  scan.geometry.stamp = stamp;
  scan.geometry.angle_min = -2.35;
  scan.geometry.angle_increment = 4.7 / 1080;
  scan.geometry.angle_max = 2.35;
  scan.geometry.range_max = 30.0;
  scan.ranges.assign(1081, 30.0f);
  return scan;
}

class SessionTest : public ::testing::Test {
 protected:
  testing::OfficeScene office{4.71238898038469};
  SessionOptions options = LoadSessionOptions(kParams);
  std::mt19937 rng{7};
};

TEST_F(SessionTest, ShippedParameterFilesCarryTheTrackerOptions) {
  for (const char* name : {"office_sick.xml", "thesis_table6.xml", "table6_weighted.xml"}) {
    const auto o = LoadSessionOptions(std::string(STRUCTLOC_SOURCE_DIR) + "/maps/params/" + name);
    EXPECT_DOUBLE_EQ(o.tracker.initial_sigma_xy_m, 0.05) << name;
    EXPECT_DOUBLE_EQ(o.tracker.initial_sigma_theta_rad, 0.03) << name;
    EXPECT_DOUBLE_EQ(o.state_period_s, 2.0) << name;
  }
}

TEST_F(SessionTest, MissingOrUnknownTrackingKeysAreErrors) {
  testing::TempDir dir;
  auto write = [&](const std::string& from, const std::string& to) {
    return testing::EditedWholeParams(dir, kParams, from, to);
  };
  EXPECT_THROW(LoadSessionOptions(write(" state_period_s=\"2\"", "")), config::ConfigError);
  EXPECT_THROW(LoadSessionOptions(write("deskew=\"true\"", "deskew=\"true\" speed=\"1\"")),
               config::ConfigError);
  EXPECT_THROW(LoadSessionOptions(write("initial_sigma_xy_m=\"0.05\"", "initial_sigma_xy_m=\"0\"")),
               config::ConfigError);
  // The localiser's loader accepts the file with its <tracking> block.
  EXPECT_NO_THROW(LoadLocaliserOptions(kParams));
}

TEST_F(SessionTest, TheInitialCovarianceComesFromTheOptions) {
  options.tracker.initial_sigma_xy_m = 0.2;
  options.tracker.initial_sigma_theta_rad = 0.1;
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  session.ExpectInitialPose(office.truth, TrackingSession::InitialPoseWhen::kAtFirstOdometry);
  EXPECT_FALSE(session.HasInitialPose());
  ASSERT_TRUE(session.AddOdometry(10.0, {0, 0, 0}, 0.0));
  ASSERT_TRUE(session.HasInitialPose());
  const auto latest = session.Latest();
  ASSERT_TRUE(latest);
  EXPECT_NEAR(latest->covariance(0, 0), 0.04, 1e-12);
  EXPECT_NEAR(latest->covariance(2, 2), 0.01, 1e-12);
  EXPECT_NEAR(latest->pose.x, office.truth.x, 1e-12);
}

// Each tracked scan says where its update's time went, stage by stage, and
// what the work between scans took (issue 37).
TEST_F(SessionTest, ATrackedScanReportsItsTimeStageByStage) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kInOrder);
  session.ExpectInitialPose(office.truth, TrackingSession::InitialPoseWhen::kAtFirstOdometry);
  const geometry::Pose2D still{0, 0, 0};
  for (int k = 0; k <= 3; ++k) ASSERT_TRUE(session.AddOdometry(0.1 * k, still, 0.0));
  for (int k = 1; k <= 2; ++k) session.AddScan(HallScan(office, 0.1 * k, rng), 0.0);
  int tracked = 0;
  while (auto report = session.Next(0.0)) {
    ASSERT_EQ(report->kind, ScanReport::Kind::kTracked);
    ++tracked;
    const auto& t = report->timings;
    double stages = 0.0;
    for (const double us : t.us) {
      EXPECT_GE(us, 0.0);
      stages += us;
    }
    EXPECT_GT(t[Stage::kExtraction], 0.0);
    EXPECT_GT(t[Stage::kCheck], 0.0);
    EXPECT_GT(t.total_cpu_us, 0.0);
    EXPECT_LE(stages, t.total_us);
    session.Anticipate();
    EXPECT_GE(session.LastAnticipateCpuUs(), 0.0);
  }
  EXPECT_EQ(tracked, 2);
}

TEST_F(SessionTest, AnInitialPoseBeforeAnyOdometryWaitsForIt) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  EXPECT_TRUE(session.WaitingForInitialPose());
  InitialPoseInput in{5.0, office.truth, Eigen::Matrix3d::Identity() * 0.01};
  EXPECT_EQ(session.SetInitialPose(in, "rt/initialpose", 0.0),
            TrackingSession::InitialPoseOutcome::kPending);
  EXPECT_FALSE(session.HasInitialPose());
  ASSERT_TRUE(session.AddOdometry(5.0, {1, 2, 0.3}, 0.0));
  EXPECT_TRUE(session.HasInitialPose());
  EXPECT_NEAR(session.Latest()->pose.y, office.truth.y, 1e-12);
  // An invalid one is refused with a sentence naming where it came from.
  in.covariance(0, 1) = 5.0;
  EXPECT_EQ(session.SetInitialPose(in, "rt/initialpose", 1.0),
            TrackingSession::InitialPoseOutcome::kRejected);
  const auto problem = session.LastProblem(2.0, 10.0);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->first, std::string("initial pose on rt/initialpose rejected: ") +
                                ToString(Rejection::kInitialPoseInvalid));
  EXPECT_DOUBLE_EQ(problem->second, 1.0);
  EXPECT_FALSE(session.LastProblem(20.0, 10.0));  // held 10 s only
}

TEST_F(SessionTest, ASavedCorrectionResumesAtTheFirstOdometryNeverTooConfident) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  const geometry::Pose2D correction{3.0, -1.0, 0.5};
  session.ResumeFrom({correction, Eigen::Vector3d(1e-6, 1e-6, 1e-6)});
  const geometry::Pose2D odom{2.0, 1.0, -0.2};
  ASSERT_TRUE(session.AddOdometry(1.0, odom, 0.0));
  const auto latest = session.Latest();
  ASSERT_TRUE(latest);
  const auto expected = geometry::Compose(correction, odom);
  EXPECT_NEAR(latest->pose.x, expected.x, 1e-9);
  EXPECT_NEAR(latest->pose.theta, expected.theta, 1e-9);
  EXPECT_NEAR(latest->covariance(0, 0), 0.05 * 0.05, 1e-12);
  EXPECT_NEAR(latest->covariance(2, 2), 0.03 * 0.03, 1e-12);
}

TEST_F(SessionTest, RefusedOdometryIsAProblemSentence) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  ASSERT_TRUE(session.AddOdometry(1.0, {0, 0, 0}, 0.0));
  EXPECT_FALSE(session.AddOdometry(1.01, {10, 0, 0}, 3.0));  // 1000 m/s
  const auto problem = session.LastProblem(3.0, 10.0);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->first,
            std::string("odometry rejected: ") + ToString(Rejection::kOdometryJump));
}

TEST_F(SessionTest, LiveTheNewestScanWinsAndTheReplacedOneIsCounted) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  session.ExpectInitialPose(office.truth, TrackingSession::InitialPoseWhen::kAtFirstOdometry);
  ASSERT_TRUE(session.AddOdometry(10.0, {0, 0, 0}, 0.0));
  session.AddScan(HallScan(office, 10.2, rng), 0.0);
  session.AddScan(HallScan(office, 10.3, rng), 0.0);
  EXPECT_EQ(session.Dropped(), 1u);
  // Not yet covered by odometry, and not waited long enough: it waits.
  EXPECT_FALSE(session.Next(0.01));
  ASSERT_TRUE(session.AddOdometry(10.4, {0, 0, 0}, 0.02));
  auto report = session.Next(0.02);
  ASSERT_TRUE(report);
  ASSERT_EQ(report->kind, ScanReport::Kind::kTracked) << report->reason;
  EXPECT_DOUBLE_EQ(report->stamp, 10.3);
  EXPECT_FALSE(report->result->lost);
  EXPECT_LT((report->pose.pose.Translation() - office.truth.Translation()).norm(), 0.02);
  EXPECT_FALSE(session.Next(0.03));  // the slot is empty
  // An inbox's own drops add up with the session's.
  SessionInputs inputs;
  inputs.dropped = 2;
  session.Apply(inputs, "rt/initialpose");
  EXPECT_EQ(session.Dropped(), 3u);
}

TEST_F(SessionTest, LiveAScanWaitsForOdometryOnlyUpToTheOdometryWait) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  session.ExpectInitialPose(office.truth, TrackingSession::InitialPoseWhen::kAtFirstOdometry);
  ASSERT_TRUE(session.AddOdometry(10.0, {0, 0, 0}, 0.0));
  auto scan = HallScan(office, 10.2, rng);
  session.AddScan(scan, 100.0);
  EXPECT_FALSE(session.Next(100.0 + 0.5 * options.tracker.odometry_wait_s));
  const auto report = session.Next(100.0 + 2 * options.tracker.odometry_wait_s);
  ASSERT_TRUE(report);
  EXPECT_EQ(report->kind, ScanReport::Kind::kRejected);
  EXPECT_EQ(report->rejection, Rejection::kNoOdometry);
  EXPECT_EQ(session.LastProblem(101.0, 10.0)->first,
            std::string("scan rejected: ") + ToString(Rejection::kNoOdometry));
}

TEST_F(SessionTest, OfflineEveryScanWaitsInOrderUntilOdometryCoversIt) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kInOrder);
  session.ExpectInitialPose(office.truth, TrackingSession::InitialPoseWhen::kAtFirstScan);
  session.AddOdometry(9.0, {0, 0, 0}, 9.0);
  session.AddScan(HallScan(office, 10.0, rng), 10.0);
  session.AddScan(HallScan(office, 10.1, rng), 10.1);
  EXPECT_EQ(session.Dropped(), 0u);
  EXPECT_FALSE(session.Next(0.0));  // odometry ends before the first scan
  EXPECT_FALSE(session.HasInitialPose());
  session.AddOdometry(10.05, {0, 0, 0}, 10.05);
  auto first = session.Next(0.0);
  ASSERT_TRUE(first);
  EXPECT_DOUBLE_EQ(first->stamp, 10.0);
  EXPECT_EQ(first->kind, ScanReport::Kind::kTracked) << first->reason;
  ASSERT_TRUE(first->odometry);
  EXPECT_TRUE(session.HasInitialPose());  // the pose of the first laser line
  EXPECT_FALSE(session.Next(0.0));
  auto last = session.Next(0.0, true);  // end of the log: what waits is processed
  ASSERT_TRUE(last);
  EXPECT_DOUBLE_EQ(last->stamp, 10.1);
}

TEST_F(SessionTest, OfflineOdometryIsInterpolatedAtAScansTime) {
  TrackingSession session(nullptr, office.options, options, Scheduling::kInOrder);
  EXPECT_FALSE(session.OdometryAt(1.0));
  session.AddOdometry(1.0, {0, 0, 0}, 1.0);
  session.AddOdometry(2.0, {1, 2, 0.2}, 2.0);
  EXPECT_FALSE(session.OdometryAt(0.5));
  const auto mid = session.OdometryAt(1.5);
  ASSERT_TRUE(mid);
  EXPECT_NEAR(mid->x, 0.5, 1e-12);
  EXPECT_NEAR(mid->y, 1.0, 1e-12);
  EXPECT_NEAR(mid->theta, 0.1, 1e-12);
  EXPECT_NEAR(session.OdometryAt(5.0)->x, 1.0, 1e-12);  // the newest beyond it
  // Only between the first and the newest sample is the pose interpolated.
  EXPECT_FALSE(session.OdometryCovers(0.5));
  EXPECT_TRUE(session.OdometryCovers(1.5));
  EXPECT_TRUE(session.OdometryCovers(2.0));
  EXPECT_FALSE(session.OdometryCovers(5.0));
}

TEST_F(SessionTest, LiveOdometryCoversOnlyStampsUpToItsNewestSample) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  EXPECT_FALSE(session.OdometryCovers(1.0));
  session.AddOdometry(1.0, {0, 0, 0}, 1.0);
  session.AddOdometry(2.0, {1, 0, 0}, 2.0);
  EXPECT_FALSE(session.OdometryCovers(0.9));
  EXPECT_TRUE(session.OdometryCovers(1.5));
  EXPECT_FALSE(session.OdometryCovers(2.1));  // OdometryAt would hold the newest sample
}

TEST_F(SessionTest, WithoutAMapScansAreCheckedAndHandedBackWithTheirOdometry) {
  TrackingSession session(nullptr, office.options, options, Scheduling::kInOrder);
  session.AddScan(EmptyRoomScan(0.5), 0.5);
  session.AddOdometry(1.0, {0, 0, 0}, 1.0);
  session.AddOdometry(2.0, {2, 0, 0}, 2.0);
  session.AddScan(EmptyRoomScan(1.5), 1.5);
  session.AddScan(EmptyRoomScan(1.4), 1.5);
  auto none = session.Next(0.0);
  ASSERT_TRUE(none);
  EXPECT_EQ(none->rejection, Rejection::kNoOdometry);
  EXPECT_FALSE(none->odometry);
  auto used = session.Next(0.0);
  ASSERT_TRUE(used);
  EXPECT_EQ(used->kind, ScanReport::Kind::kUntracked);
  EXPECT_NEAR(used->odometry->x, 1.0, 1e-12);
  EXPECT_EQ(used->scan.ranges.size(), 1081u);
  auto late = session.Next(0.0, true);
  ASSERT_TRUE(late);
  EXPECT_EQ(late->kind, ScanReport::Kind::kRejected);
  EXPECT_EQ(late->rejection, Rejection::kScanOutOfOrder);
}

TEST_F(SessionTest, LostTimersRunFromTheFirstLostScan) {
  options.tracker.lost_sigma_m = 1e-6;  // every scan without a usable match is lost
  TrackingSession session(&office.world, office.options, options, Scheduling::kInOrder);
  session.ExpectInitialPose(office.truth, TrackingSession::InitialPoseWhen::kAtFirstScan);
  for (int k = 0; k <= 40; ++k) session.AddOdometry(10.0 + 0.1 * k, {0, 0, 0}, 0.0);
  session.AddScan(HallScan(office, 10.0, rng), 0.0);
  for (int k = 1; k <= 3; ++k) session.AddScan(EmptyRoomScan(10.0 + k), 0.0);
  session.AddScan(HallScan(office, 13.5, rng), 0.0);
  std::vector<ScanReport> reports;
  while (auto r = session.Next(0.0, true)) reports.push_back(std::move(*r));
  ASSERT_EQ(reports.size(), 5u);
  for (const auto& r : reports) ASSERT_EQ(r.kind, ScanReport::Kind::kTracked) << r.reason;
  EXPECT_FALSE(reports[0].result == nullptr);
  EXPECT_EQ(session.LostPeriods(), 1u);
  EXPECT_DOUBLE_EQ(session.LostSeconds(), 2.0);  // lost at 11, 12 and 13
  EXPECT_FALSE(session.Lost());                  // found again at 13.5
}

TEST_F(SessionTest, LiveLostForCountsFromTheFirstLostUpdate) {
  options.lost_error_after_s = 5.0;
  options.tracker.lost_sigma_m = 1e-6;  // every scan without a usable match is lost
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  session.ExpectInitialPose(office.truth, TrackingSession::InitialPoseWhen::kAtFirstOdometry);
  ASSERT_TRUE(session.AddOdometry(10.0, {0, 0, 0}, 0.0));
  ASSERT_TRUE(session.AddOdometry(12.0, {0, 0, 0}, 0.0));
  session.AddScan(EmptyRoomScan(11.0), 100.0);
  const auto report = session.Next(100.0);
  ASSERT_TRUE(report);
  ASSERT_EQ(report->kind, ScanReport::Kind::kTracked) << report->reason;
  ASSERT_TRUE(session.Lost());
  EXPECT_FALSE(session.LostReason().empty());
  EXPECT_DOUBLE_EQ(session.LostFor(103.0), 3.0);
  EXPECT_FALSE(session.LostTooLong(104.0));
  EXPECT_TRUE(session.LostTooLong(106.0));
}

TEST_F(SessionTest, ThePoseIsDueToBeSavedEveryStatePeriod) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  EXPECT_FALSE(session.StateToSave(0.0));  // nothing to save yet
  session.ExpectInitialPose(office.truth, TrackingSession::InitialPoseWhen::kAtFirstOdometry);
  ASSERT_TRUE(session.AddOdometry(1.0, {1, 0, 0}, 0.0));
  const auto first = session.StateToSave(50.0);
  ASSERT_TRUE(first);
  EXPECT_NEAR(geometry::Compose(first->map_to_odom, {1, 0, 0}).x, office.truth.x, 1e-9);
  EXPECT_NEAR(first->variance.x(), 0.05 * 0.05, 1e-12);
  EXPECT_FALSE(session.StateToSave(50.0 + 0.5 * options.state_period_s));
  EXPECT_TRUE(session.StateToSave(50.0 + options.state_period_s));
}

TEST(SessionInbox, ListenersOnlyLeaveInputsAndTheNewestScanWins) {
  SessionInbox inbox;
  inbox.OfferOdometry(1.0, {0, 0, 0}, 5.0);
  inbox.OfferScan(EmptyRoomScan(1.0), 5.1);
  inbox.OfferScan(EmptyRoomScan(1.1), 5.2);
  inbox.OfferInitialPose({1.0, {1, 1, 0}, Eigen::Matrix3d::Identity()});
  EXPECT_DOUBLE_EQ(inbox.LastScanArrival(), 5.2);
  EXPECT_DOUBLE_EQ(inbox.LastOdometryArrival(), 5.0);
  SessionInputs inputs;
  ASSERT_TRUE(inbox.WaitAndTake(std::chrono::milliseconds(0), inputs));
  ASSERT_TRUE(inputs.scan);
  EXPECT_DOUBLE_EQ(inputs.scan->geometry.stamp, 1.1);
  EXPECT_DOUBLE_EQ(inputs.scan_arrived_s, 5.2);
  EXPECT_EQ(inputs.dropped, 1u);
  EXPECT_EQ(inputs.odometry.size(), 1u);
  EXPECT_EQ(inputs.initial_poses.size(), 1u);
  ASSERT_TRUE(inbox.WaitAndTake(std::chrono::milliseconds(0), inputs));
  EXPECT_FALSE(inputs.scan);  // taken once
  EXPECT_EQ(inputs.dropped, 0u);
  inbox.Stop();
  EXPECT_FALSE(inbox.WaitAndTake(std::chrono::milliseconds(1000), inputs));
}

}  // namespace
}  // namespace structloc::localisation_core
