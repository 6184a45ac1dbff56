// The localisation component's message conversions, without a participant:
// what a subscriber on any DDS stack reads is what the core computed, in
// ROS 2's layouts (stamps, quaternions, the 6x6 covariance, frame ids), and
// what arrives from the robot becomes the core's input unchanged.
#include <gtest/gtest.h>

#include <cmath>

#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/localisation/localisation_conversions.hpp"

namespace structloc::localisation {
namespace {

dds_common::FrameIds Frames() {
  dds_common::FrameIds f;
  f.map = "site_map";
  f.odom = "wheel_odom";
  f.base_link = "chassis";
  f.laser = "front_laser";
  return f;
}

builtin_interfaces::msg::Time Stamp(int32_t sec, uint32_t nanosec) {
  builtin_interfaces::msg::Time t;
  t.sec(sec);
  t.nanosec(nanosec);
  return t;
}

TEST(LocalisationConversions, ALaserScanBecomesTheTrackersScanWithItsOwnGeometry) {
  sensor_msgs::msg::LaserScan msg;
  msg.header().stamp(Stamp(1700000000, 250000000));
  msg.angle_min(-2.35f);
  msg.angle_max(2.35f);
  msg.angle_increment(0.00436f);
  msg.time_increment(1.7e-5f);
  msg.range_min(0.1f);
  msg.range_max(30.0f);
  msg.ranges({1.0f, 2.5f, NAN, 31.0f});
  const auto in = FromLaserScan(msg);
  EXPECT_DOUBLE_EQ(in.stamp, 1700000000.25);
  EXPECT_FLOAT_EQ(static_cast<float>(in.angle_min), -2.35f);
  EXPECT_FLOAT_EQ(static_cast<float>(in.angle_max), 2.35f);
  EXPECT_FLOAT_EQ(static_cast<float>(in.angle_increment), 0.00436f);
  EXPECT_FLOAT_EQ(static_cast<float>(in.time_increment), 1.7e-5f);
  EXPECT_FLOAT_EQ(static_cast<float>(in.range_min), 0.1f);
  EXPECT_FLOAT_EQ(static_cast<float>(in.range_max), 30.0f);
  EXPECT_EQ(in.ranges, msg.ranges().data());  // not copied
  EXPECT_EQ(in.count, 4u);
  // The scan that waits in the session owns a copy of its ranges.
  const auto waiting = ToSessionScan(msg);
  EXPECT_EQ(waiting.geometry.ranges, nullptr);
  EXPECT_EQ(waiting.geometry.count, 0u);
  EXPECT_DOUBLE_EQ(waiting.geometry.stamp, in.stamp);
  ASSERT_EQ(waiting.ranges.size(), 4u);
  EXPECT_EQ(waiting.ranges[1], 2.5f);
  EXPECT_TRUE(std::isnan(waiting.ranges[2]));
}

TEST(LocalisationConversions, OdometryAndAnInitialPoseGivePlanarPosesAndTheXYYawCovariance) {
  nav_msgs::msg::Odometry odom;
  odom.header().stamp(Stamp(12, 500000000));
  odom.pose().pose().position().x(3.0);
  odom.pose().pose().position().y(-4.0);
  odom.pose().pose().orientation(dds_common::ToQuaternion(2.5));
  const auto o = FromOdometry(odom);
  EXPECT_DOUBLE_EQ(o.stamp, 12.5);
  EXPECT_DOUBLE_EQ(o.pose.x, 3.0);
  EXPECT_DOUBLE_EQ(o.pose.y, -4.0);
  EXPECT_NEAR(o.pose.theta, 2.5, 1e-12);

  geometry_msgs::msg::PoseWithCovarianceStamped initial;
  initial.header().stamp(Stamp(7, 0));
  initial.pose().pose().position().x(1.0);
  initial.pose().pose().orientation(dds_common::ToQuaternion(-3.0));
  auto& c = initial.pose().covariance();
  for (size_t i = 0; i < 36; ++i) c[i] = 100.0 + static_cast<double>(i);  // z, roll, pitch: noise
  c[0] = 0.04;                                                            // x x
  c[1] = c[6] = 0.01;                                                     // x y
  c[7] = 0.09;                                                            // y y
  c[5] = c[30] = 0.002;                                                   // x yaw
  c[11] = c[31] = -0.003;                                                 // y yaw
  c[35] = 0.0025;                                                         // yaw yaw
  Eigen::Matrix3d cov;
  const auto p = FromPoseWithCovariance(initial, &cov);
  EXPECT_DOUBLE_EQ(p.stamp, 7.0);
  EXPECT_DOUBLE_EQ(p.pose.x, 1.0);
  EXPECT_NEAR(p.pose.theta, -3.0, 1e-12);
  Eigen::Matrix3d expected;
  expected << 0.04, 0.01, 0.002, 0.01, 0.09, -0.003, 0.002, -0.003, 0.0025;
  EXPECT_EQ(cov, expected);
}

TEST(LocalisationConversions, APublishedPoseReadsBackAndItsCovarianceIsExactlySymmetric) {
  localisation_core::TrackedPose t;
  t.stamp = 1234.000001;
  t.pose = {-7.25, 0.5, 3.1};
  t.covariance << 1e-4, 2e-6, 3e-7, 2.0000001e-6, 4e-4, -1e-6, 3e-7, -1e-6, 9e-5;
  const auto msg = ToPoseWithCovarianceStamped(t, Frames());
  EXPECT_EQ(msg.header().frame_id(), "site_map");
  EXPECT_NEAR(dds_common::FromRosTime(msg.header().stamp()), t.stamp, 1e-9);
  EXPECT_DOUBLE_EQ(msg.pose().pose().position().z(), 0.0);
  const auto& c = msg.pose().covariance();
  for (size_t r = 0; r < 6; ++r) {
    for (size_t k = 0; k < 6; ++k) EXPECT_EQ(c[r * 6 + k], c[k * 6 + r]) << r << " " << k;
  }
  EXPECT_EQ(c[14], 1e6);  // z, roll and pitch are not estimated
  EXPECT_EQ(c[21], 1e6);
  EXPECT_EQ(c[28], 1e6);
  Eigen::Matrix3d back;
  const auto p = FromPoseWithCovariance(msg, &back);
  EXPECT_DOUBLE_EQ(p.pose.x, t.pose.x);
  EXPECT_DOUBLE_EQ(p.pose.y, t.pose.y);
  EXPECT_NEAR(p.pose.theta, t.pose.theta, 1e-12);
  EXPECT_TRUE(back.isApprox(0.5 * (t.covariance + t.covariance.transpose()), 1e-15));
}

TEST(LocalisationConversions, TheMapToOdomTransformNamesItsFrames) {
  const auto msg = ToMapToOdomTf({2.0, -1.0, 0.75}, 50.5, Frames());
  ASSERT_EQ(msg.transforms().size(), 1u);
  const auto& tf = msg.transforms()[0];
  EXPECT_EQ(tf.header().frame_id(), "site_map");
  EXPECT_EQ(tf.child_frame_id(), "wheel_odom");
  EXPECT_DOUBLE_EQ(dds_common::FromRosTime(tf.header().stamp()), 50.5);
  EXPECT_DOUBLE_EQ(tf.transform().translation().x(), 2.0);
  EXPECT_DOUBLE_EQ(tf.transform().translation().y(), -1.0);
  EXPECT_NEAR(dds_common::YawFromQuaternion(tf.transform().rotation()), 0.75, 1e-12);
}

localisation_core::LocalisationResult AResult() {
  localisation_core::LocalisationResult r;
  r.quality = 0.8;
  localisation_core::FeatureKindResult walls;
  walls.kind = "walls";
  walls.shape = localisation_core::FeatureShape::kLine;
  walls.expected = 5;
  walls.extract_us = 12.5;
  localisation_core::FeatureMatch wall;
  wall.model_id = 17;
  wall.members = 40;
  wall.r_m = 2.5;
  wall.alpha_rad = -1.2;
  wall.residual_m = 0.003;
  walls.matches = {wall, wall};
  localisation_core::FeatureKindResult pillars;
  pillars.kind = "cylinders";
  pillars.shape = localisation_core::FeatureShape::kPoint;
  pillars.expected = 2;
  localisation_core::FeatureMatch pillar;
  pillar.model_id = 3;
  pillar.members = 9;
  pillar.x_m = 1.5;
  pillar.y_m = -0.5;
  pillar.radius_m = 0.25;
  pillars.matches = {pillar};
  r.features = {walls, pillars};
  r.times.prefilter_us = 1.0;
  r.times.line_fit_us = 2.0;
  r.times.solve_us = 3.0;
  r.times.total_us = 20.0;
  return r;
}

TEST(LocalisationConversions, FeaturesKeepEachKindsMatchesInTheLaserFrame) {
  const auto msg = ToScanFeatures(AResult(), 9.0, Frames());
  EXPECT_EQ(msg.header().frame_id(), "front_laser");
  ASSERT_EQ(msg.kinds().size(), 2u);
  EXPECT_EQ(msg.kinds()[0].kind(), "walls");
  ASSERT_EQ(msg.kinds()[0].lines().size(), 2u);
  EXPECT_TRUE(msg.kinds()[0].points().empty());
  const auto& w = msg.kinds()[0].lines()[0];
  EXPECT_EQ(w.model_id(), 17);
  EXPECT_EQ(w.member_count(), 40u);
  EXPECT_DOUBLE_EQ(w.r_m(), 2.5);
  EXPECT_DOUBLE_EQ(w.alpha_rad(), -1.2);
  EXPECT_DOUBLE_EQ(w.residual_m(), 0.003);
  EXPECT_EQ(msg.kinds()[1].kind(), "cylinders");
  ASSERT_EQ(msg.kinds()[1].points().size(), 1u);
  EXPECT_TRUE(msg.kinds()[1].lines().empty());
  const auto& p = msg.kinds()[1].points()[0];
  EXPECT_DOUBLE_EQ(p.x_m(), 1.5);
  EXPECT_DOUBLE_EQ(p.y_m(), -0.5);
  EXPECT_DOUBLE_EQ(p.radius_m(), 0.25);
  EXPECT_EQ(p.member_count(), 9u);
}

TEST(LocalisationConversions, TheStatusCountsFeaturesScansAndTimesAndSaysWhyLost) {
  localisation_core::TrackerStats stats;
  stats.scans_processed = 100;
  stats.rejected[static_cast<size_t>(localisation_core::Rejection::kEmptyScan)] = 2;
  stats.rejected[static_cast<size_t>(localisation_core::Rejection::kScanOutOfOrder)] = 3;
  auto s = ToStatus(AResult(), "", stats, 4, 9.0, Frames());
  EXPECT_EQ(s.header().frame_id(), "site_map");
  EXPECT_EQ(s.phase(), "tracking");
  EXPECT_FALSE(s.lost());
  EXPECT_EQ(s.lost_reason(), "");
  EXPECT_DOUBLE_EQ(s.quality(), 0.8);
  ASSERT_EQ(s.features().size(), 2u);
  EXPECT_EQ(s.features()[0].kind(), "walls");
  EXPECT_EQ(s.features()[0].matched(), 2u);
  EXPECT_EQ(s.features()[0].expected(), 5u);
  EXPECT_EQ(s.features()[1].matched(), 1u);
  EXPECT_EQ(s.scans_processed(), 100u);
  EXPECT_EQ(s.scans_dropped(), 4u);
  EXPECT_EQ(s.scans_rejected(), 5u);
  EXPECT_DOUBLE_EQ(s.timings().total_us(), 20.0);
  ASSERT_EQ(s.timings().features().size(), 2u);
  EXPECT_DOUBLE_EQ(s.timings().features()[0].extract_us(), 12.5);
  s = ToStatus(AResult(), "no features matched", stats, 0, 9.0, Frames());
  EXPECT_TRUE(s.lost());
  EXPECT_EQ(s.lost_reason(), "no features matched");
  s = ToStatus(AResult(), nullptr, stats, 0, 9.0, Frames());
  EXPECT_FALSE(s.lost());
}

TEST(LocalisationConversions, HypothesesKeepTheirOrderAndTheirWeightsSumToOne) {
  std::vector<localisation_core::Hypothesis> held(3);
  held[0].pose = {1.0, 2.0, 0.5};
  held[0].log_likelihood = -10.0;
  held[1].pose = {-1.0, -2.0, -2.6};
  held[1].log_likelihood = -10.0 - std::log(3.0);  // a third as likely
  held[2].pose = {5.0, 5.0, 3.0};
  held[2].log_likelihood = -2000.0;  // would underflow without the best subtracted
  const auto poses = ToPoseArray(held, 3.0, Frames());
  EXPECT_EQ(poses.header().frame_id(), "site_map");
  ASSERT_EQ(poses.poses().size(), 3u);
  EXPECT_DOUBLE_EQ(poses.poses()[1].position().x(), -1.0);
  EXPECT_NEAR(dds_common::YawFromQuaternion(poses.poses()[1].orientation()), -2.6, 1e-12);
  const auto status = ToStartUpStatus(held, 3.0, Frames());
  EXPECT_EQ(status.phase(), "holding");
  EXPECT_TRUE(status.lost());
  EXPECT_NE(status.lost_reason().find("3 hypotheses"), std::string::npos) << status.lost_reason();
  ASSERT_EQ(status.hypothesis_weights().size(), 3u);
  EXPECT_NEAR(status.hypothesis_weights()[0], 0.75, 1e-12);
  EXPECT_NEAR(status.hypothesis_weights()[1], 0.25, 1e-12);
  EXPECT_GE(status.hypothesis_weights()[2], 0.0);
  EXPECT_LT(status.hypothesis_weights()[2], 1e-12);
  const auto searching = ToStartUpStatus({}, 3.0, Frames());
  EXPECT_EQ(searching.phase(), "searching");
  EXPECT_TRUE(searching.hypothesis_weights().empty());
}

TEST(LocalisationConversions, HealthKeepsItsLevelMessageAndValues) {
  localisation_core::SessionHealth health;
  health.level = localisation_core::HealthLevel::kWarn;
  health.message = "no scans for 0.7 s";
  health.values = {{"scans_processed", "12"}};
  auto report = ToHealthReport(health);
  EXPECT_EQ(report.level, dds_common::HealthLevel::kWarn);
  EXPECT_EQ(report.message, "no scans for 0.7 s");
  EXPECT_EQ(report.values, health.values);
  health.level = localisation_core::HealthLevel::kError;
  EXPECT_EQ(ToHealthReport(health).level, dds_common::HealthLevel::kError);
  health.level = localisation_core::HealthLevel::kOk;
  EXPECT_EQ(ToHealthReport(health).level, dds_common::HealthLevel::kOk);
}

}  // namespace
}  // namespace structloc::localisation
