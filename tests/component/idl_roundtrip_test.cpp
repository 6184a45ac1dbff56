// Round-trips one sample of every IDL type through real DataWriter/DataReader
// pairs on loopback and checks every field, the ROS 2 DDS type names and the
// rt/ topic names.
#include <gtest/gtest.h>

#include <cmath>

#include "builtin_interfaces/msg/TimePubSubTypes.h"
#include "dds_test_support.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "diagnostic_msgs/msg/DiagnosticStatusPubSubTypes.h"
#include "diagnostic_msgs/msg/KeyValuePubSubTypes.h"
#include "geometry_msgs/msg/PointPubSubTypes.h"
#include "geometry_msgs/msg/PosePubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovariancePubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "geometry_msgs/msg/QuaternionPubSubTypes.h"
#include "geometry_msgs/msg/TransformPubSubTypes.h"
#include "geometry_msgs/msg/TransformStampedPubSubTypes.h"
#include "geometry_msgs/msg/TwistPubSubTypes.h"
#include "geometry_msgs/msg/TwistWithCovariancePubSubTypes.h"
#include "geometry_msgs/msg/Vector3PubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "std_msgs/msg/EmptyPubSubTypes.h"
#include "std_msgs/msg/HeaderPubSubTypes.h"
#include "structloc_msgs/msg/CalibrationResultPubSubTypes.h"
#include "structloc_msgs/msg/FeatureCountPubSubTypes.h"
#include "structloc_msgs/msg/FeatureSetPubSubTypes.h"
#include "structloc_msgs/msg/FeatureTimingPubSubTypes.h"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"
#include "structloc_msgs/msg/PointFeaturePubSubTypes.h"
#include "structloc_msgs/msg/RobotParametersPubSubTypes.h"
#include "structloc_msgs/msg/ScanFeaturesPubSubTypes.h"
#include "structloc_msgs/msg/StepTimingsPubSubTypes.h"
#include "structloc_msgs/msg/WallFeaturePubSubTypes.h"
#include "structloc_msgs/msg/WheelEncodersPubSubTypes.h"
#include "test_domains.hpp"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

namespace structloc {
namespace {

using testing::RoundTrip;
using testing::TestNodeOptions;

constexpr int kDomain = testing::domains::kIdlRoundtrip;

// Distinct, non-default values for every field, so a swapped or dropped field shows.
class Filler {
 public:
  double D() { return 0.125 * ++n_; }
  float F() { return 0.5f * static_cast<float>(++n_); }
  uint32_t U() { return 1000u + ++n_; }
  std::string S() { return "s" + std::to_string(++n_); }

  builtin_interfaces::msg::Time Time() {
    builtin_interfaces::msg::Time t;
    t.sec(-static_cast<int32_t>(U()));
    t.nanosec(999999000u + (++n_ % 999));
    return t;
  }
  std_msgs::msg::Header Header() {
    std_msgs::msg::Header h;
    h.stamp(Time());
    h.frame_id(S());
    return h;
  }
  geometry_msgs::msg::Point Point() {
    geometry_msgs::msg::Point p;
    p.x(D());
    p.y(D());
    p.z(D());
    return p;
  }
  geometry_msgs::msg::Vector3 Vector3() {
    geometry_msgs::msg::Vector3 v;
    v.x(D());
    v.y(D());
    v.z(D());
    return v;
  }
  geometry_msgs::msg::Quaternion Quaternion() {
    geometry_msgs::msg::Quaternion q;
    q.x(D());
    q.y(D());
    q.z(D());
    q.w(D());
    return q;
  }
  geometry_msgs::msg::Pose Pose() {
    geometry_msgs::msg::Pose p;
    p.position(Point());
    p.orientation(Quaternion());
    return p;
  }
  geometry_msgs::msg::PoseWithCovariance PoseWithCovariance() {
    geometry_msgs::msg::PoseWithCovariance p;
    p.pose(Pose());
    for (auto& c : p.covariance()) c = D();
    return p;
  }
  geometry_msgs::msg::PoseWithCovarianceStamped PoseWithCovarianceStamped() {
    geometry_msgs::msg::PoseWithCovarianceStamped p;
    p.header(Header());
    p.pose(PoseWithCovariance());
    return p;
  }
  geometry_msgs::msg::Twist Twist() {
    geometry_msgs::msg::Twist t;
    t.linear(Vector3());
    t.angular(Vector3());
    return t;
  }
  geometry_msgs::msg::TwistWithCovariance TwistWithCovariance() {
    geometry_msgs::msg::TwistWithCovariance t;
    t.twist(Twist());
    for (auto& c : t.covariance()) c = D();
    return t;
  }
  geometry_msgs::msg::Transform Transform() {
    geometry_msgs::msg::Transform t;
    t.translation(Vector3());
    t.rotation(Quaternion());
    return t;
  }
  geometry_msgs::msg::TransformStamped TransformStamped() {
    geometry_msgs::msg::TransformStamped t;
    t.header(Header());
    t.child_frame_id(S());
    t.transform(Transform());
    return t;
  }
  nav_msgs::msg::Odometry Odometry() {
    nav_msgs::msg::Odometry o;
    o.header(Header());
    o.child_frame_id(S());
    o.pose(PoseWithCovariance());
    o.twist(TwistWithCovariance());
    return o;
  }
  sensor_msgs::msg::LaserScan LaserScan() {
    sensor_msgs::msg::LaserScan s;
    s.header(Header());
    s.angle_min(F());
    s.angle_max(F());
    s.angle_increment(F());
    s.time_increment(F());
    s.scan_time(F());
    s.range_min(F());
    s.range_max(F());
    for (int i = 0; i < 1081; ++i) s.ranges().push_back(F());
    s.ranges()[3] = std::numeric_limits<float>::infinity();
    for (int i = 0; i < 1081; ++i) s.intensities().push_back(F());
    return s;
  }
  tf2_msgs::msg::TFMessage TFMessage() {
    tf2_msgs::msg::TFMessage m;
    m.transforms().push_back(TransformStamped());
    m.transforms().push_back(TransformStamped());
    return m;
  }
  diagnostic_msgs::msg::KeyValue KeyValue() {
    diagnostic_msgs::msg::KeyValue kv;
    kv.key(S());
    kv.value(S());
    return kv;
  }
  diagnostic_msgs::msg::DiagnosticStatus DiagnosticStatus() {
    diagnostic_msgs::msg::DiagnosticStatus s;
    s.level(2);
    s.name(S());
    s.message(S());
    s.hardware_id(S());
    s.values().push_back(KeyValue());
    s.values().push_back(KeyValue());
    return s;
  }
  diagnostic_msgs::msg::DiagnosticArray DiagnosticArray() {
    diagnostic_msgs::msg::DiagnosticArray a;
    a.header(Header());
    a.status().push_back(DiagnosticStatus());
    return a;
  }
  structloc_msgs::msg::WheelEncoders WheelEncoders() {
    structloc_msgs::msg::WheelEncoders e;
    e.header(Header());
    e.traction_ticks(4294967290u);
    e.traction_counter_bits(32);
    e.steering_ticks(-static_cast<int32_t>(U()));
    e.traction_angle_increment_rad(D());
    e.steering_angle_rad(-D());
    e.differential(true);
    e.left_ticks(4294967291u);
    e.right_ticks(U());
    return e;
  }
  structloc_msgs::msg::WallFeature WallFeature() {
    structloc_msgs::msg::WallFeature w;
    w.r_m(D());
    w.alpha_rad(-D());
    w.member_count(U());
    w.model_id(-1);
    w.residual_m(D());
    return w;
  }
  structloc_msgs::msg::PointFeature PointFeature() {
    structloc_msgs::msg::PointFeature p;
    p.x_m(D());
    p.y_m(-D());
    p.radius_m(D());
    p.member_count(U());
    p.model_id(static_cast<int32_t>(U()));
    p.residual_m(D());
    return p;
  }
  structloc_msgs::msg::ScanFeatures ScanFeatures() {
    structloc_msgs::msg::ScanFeatures f;
    f.header(Header());
    structloc_msgs::msg::FeatureSet walls;
    walls.kind(S());
    walls.lines().push_back(WallFeature());
    walls.lines().push_back(WallFeature());
    f.kinds().push_back(walls);
    structloc_msgs::msg::FeatureSet points;
    points.kind(S());
    points.points().push_back(PointFeature());
    points.points().push_back(PointFeature());
    f.kinds().push_back(points);
    return f;
  }
  structloc_msgs::msg::StepTimings StepTimings() {
    structloc_msgs::msg::StepTimings t;
    t.prefilter_us(D());
    t.line_fit_us(D());
    for (int i = 0; i < 3; ++i) {
      structloc_msgs::msg::FeatureTiming k;
      k.kind(S());
      k.extract_us(D());
      t.features().push_back(k);
    }
    t.solve_us(D());
    t.total_us(D());
    return t;
  }
  structloc_msgs::msg::LocalisationStatus LocalisationStatus() {
    structloc_msgs::msg::LocalisationStatus s;
    s.header(Header());
    s.quality(D());
    s.lost(true);
    s.lost_reason(S());
    for (int i = 0; i < 3; ++i) {
      structloc_msgs::msg::FeatureCount c;
      c.kind(S());
      c.matched(U());
      c.expected(U());
      s.features().push_back(c);
    }
    s.scans_processed(U() + 0x100000000ull);
    s.scans_dropped(U());
    s.scans_rejected(U());
    s.timings(StepTimings());
    return s;
  }
  structloc_msgs::msg::RobotParameters RobotParameters() {
    structloc_msgs::msg::RobotParameters p;
    p.wheel_radius_m(D());
    p.axle_distance_m(D());
    p.steering_offset_rad(-D());
    p.steering_rad_per_tick(D());
    p.sensor_x_m(D());
    p.sensor_y_m(-D());
    p.sensor_theta_rad(D());
    p.differential(true);
    p.left_wheel_radius_m(D());
    p.right_wheel_radius_m(D());
    p.wheel_separation_m(D());
    return p;
  }
  structloc_msgs::msg::CalibrationResult CalibrationResult() {
    structloc_msgs::msg::CalibrationResult c;
    c.header(Header());
    c.success(true);
    c.parameters(RobotParameters());
    c.standard_deviations(RobotParameters());
    c.residual_rms_before(D());
    c.residual_rms_after(D());
    c.fixes_used(U());
    c.fixes_rejected(U());
    c.warnings().push_back(S());
    c.warnings().push_back(S());
    c.estimated().push_back(S());
    c.estimated().push_back(S());
    for (int k = 0; k < 4; ++k) c.covariance().push_back(-D());
    c.window_start(Time());
    c.window_end(Time());
    c.changed().push_back(S());
    return c;
  }

 private:
  int n_ = 0;
};

class IdlRoundTrip : public ::testing::Test {
 protected:
  IdlRoundTrip()
      : writer_(TestNodeOptions("roundtrip_writer", kDomain)),
        reader_(TestNodeOptions("roundtrip_reader", kDomain)) {}

  template <class PubSubType>
  void ExpectRoundTrip(const dds_common::TopicSpec& topic, const std::string& expected_type_name,
                       const typename PubSubType::type& sample) {
    PubSubType type_support;
    EXPECT_EQ(type_support.getName(), expected_type_name);
    auto received = RoundTrip<PubSubType>(writer_, reader_, topic, sample);
    ASSERT_TRUE(received.has_value()) << "nothing received on " << topic.name;
    EXPECT_TRUE(*received == sample) << "a field changed on the wire on " << topic.name;
  }

  dds_common::Node writer_;
  dds_common::Node reader_;
  Filler fill_;
};

dds_common::TopicSpec TestTopic(const std::string& name) {
  return {"rt/structloc_test/" + name, "reliable_state"};
}

TEST_F(IdlRoundTrip, LaserScanOnRtScan) {
  EXPECT_EQ(dds_common::topics::kScan.name, "rt/scan");
  const auto sample = fill_.LaserScan();
  ExpectRoundTrip<sensor_msgs::msg::LaserScanPubSubType>(
      dds_common::topics::kScan, "sensor_msgs::msg::dds_::LaserScan_", sample);
}

TEST_F(IdlRoundTrip, OdometryOnRtOdom) {
  EXPECT_EQ(dds_common::topics::kOdom.name, "rt/odom");
  ExpectRoundTrip<nav_msgs::msg::OdometryPubSubType>(
      dds_common::topics::kOdom, "nav_msgs::msg::dds_::Odometry_", fill_.Odometry());
}

TEST_F(IdlRoundTrip, PoseWithCovarianceStampedOnRtPoseAndInitialPose) {
  EXPECT_EQ(dds_common::topics::kPose.name, "rt/pose");
  EXPECT_EQ(dds_common::topics::kInitialPose.name, "rt/initialpose");
  ExpectRoundTrip<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      dds_common::topics::kPose, "geometry_msgs::msg::dds_::PoseWithCovarianceStamped_",
      fill_.PoseWithCovarianceStamped());
  ExpectRoundTrip<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      dds_common::topics::kInitialPose, "geometry_msgs::msg::dds_::PoseWithCovarianceStamped_",
      fill_.PoseWithCovarianceStamped());
}

TEST_F(IdlRoundTrip, EmptyOnRtReinitializeGlobalLocalization) {
  EXPECT_EQ(dds_common::topics::kReinitializeGlobalLocalization.name,
            "rt/reinitialize_global_localization");
  std_msgs::msg::Empty sample;
  sample.structure_needs_at_least_one_member(7);
  ExpectRoundTrip<std_msgs::msg::EmptyPubSubType>(
      dds_common::topics::kReinitializeGlobalLocalization, "std_msgs::msg::dds_::Empty_", sample);
}

TEST_F(IdlRoundTrip, TFMessageOnRtTf) {
  EXPECT_EQ(dds_common::topics::kTf.name, "rt/tf");
  ExpectRoundTrip<tf2_msgs::msg::TFMessagePubSubType>(
      dds_common::topics::kTf, "tf2_msgs::msg::dds_::TFMessage_", fill_.TFMessage());
}

TEST_F(IdlRoundTrip, DiagnosticArrayOnRtDiagnostics) {
  EXPECT_EQ(dds_common::topics::kDiagnostics.name, "rt/diagnostics");
  ExpectRoundTrip<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
      dds_common::topics::kDiagnostics, "diagnostic_msgs::msg::dds_::DiagnosticArray_",
      fill_.DiagnosticArray());
}

TEST_F(IdlRoundTrip, TwistOnRtCmdVel) {
  EXPECT_EQ(dds_common::topics::kCmdVel.name, "rt/cmd_vel");
  ExpectRoundTrip<geometry_msgs::msg::TwistPubSubType>(
      dds_common::topics::kCmdVel, "geometry_msgs::msg::dds_::Twist_", fill_.Twist());
}

TEST_F(IdlRoundTrip, NestedRosTypesOnTheirOwn) {
  ExpectRoundTrip<builtin_interfaces::msg::TimePubSubType>(
      TestTopic("time"), "builtin_interfaces::msg::dds_::Time_", fill_.Time());
  ExpectRoundTrip<std_msgs::msg::HeaderPubSubType>(TestTopic("header"),
                                                   "std_msgs::msg::dds_::Header_", fill_.Header());
  ExpectRoundTrip<geometry_msgs::msg::PointPubSubType>(
      TestTopic("point"), "geometry_msgs::msg::dds_::Point_", fill_.Point());
  ExpectRoundTrip<geometry_msgs::msg::QuaternionPubSubType>(
      TestTopic("quaternion"), "geometry_msgs::msg::dds_::Quaternion_", fill_.Quaternion());
  ExpectRoundTrip<geometry_msgs::msg::PosePubSubType>(
      TestTopic("pose"), "geometry_msgs::msg::dds_::Pose_", fill_.Pose());
  ExpectRoundTrip<geometry_msgs::msg::PoseWithCovariancePubSubType>(
      TestTopic("pose_cov"), "geometry_msgs::msg::dds_::PoseWithCovariance_",
      fill_.PoseWithCovariance());
  ExpectRoundTrip<geometry_msgs::msg::Vector3PubSubType>(
      TestTopic("vector3"), "geometry_msgs::msg::dds_::Vector3_", fill_.Vector3());
  ExpectRoundTrip<geometry_msgs::msg::TwistWithCovariancePubSubType>(
      TestTopic("twist_cov"), "geometry_msgs::msg::dds_::TwistWithCovariance_",
      fill_.TwistWithCovariance());
  ExpectRoundTrip<geometry_msgs::msg::TransformPubSubType>(
      TestTopic("transform"), "geometry_msgs::msg::dds_::Transform_", fill_.Transform());
  ExpectRoundTrip<geometry_msgs::msg::TransformStampedPubSubType>(
      TestTopic("transform_stamped"), "geometry_msgs::msg::dds_::TransformStamped_",
      fill_.TransformStamped());
  ExpectRoundTrip<diagnostic_msgs::msg::KeyValuePubSubType>(
      TestTopic("key_value"), "diagnostic_msgs::msg::dds_::KeyValue_", fill_.KeyValue());
  ExpectRoundTrip<diagnostic_msgs::msg::DiagnosticStatusPubSubType>(
      TestTopic("diagnostic_status"), "diagnostic_msgs::msg::dds_::DiagnosticStatus_",
      fill_.DiagnosticStatus());
}

TEST_F(IdlRoundTrip, StructlocMessages) {
  EXPECT_EQ(dds_common::topics::kWheelEncoders.name, "rt/wheel_encoders");
  ExpectRoundTrip<structloc_msgs::msg::WheelEncodersPubSubType>(
      dds_common::topics::kWheelEncoders, "structloc_msgs::msg::dds_::WheelEncoders_",
      fill_.WheelEncoders());
  ExpectRoundTrip<structloc_msgs::msg::ScanFeaturesPubSubType>(
      dds_common::topics::kFeatures, "structloc_msgs::msg::dds_::ScanFeatures_",
      fill_.ScanFeatures());
  ExpectRoundTrip<structloc_msgs::msg::LocalisationStatusPubSubType>(
      dds_common::topics::kStatus, "structloc_msgs::msg::dds_::LocalisationStatus_",
      fill_.LocalisationStatus());
  ExpectRoundTrip<structloc_msgs::msg::CalibrationResultPubSubType>(
      dds_common::topics::kCalibration, "structloc_msgs::msg::dds_::CalibrationResult_",
      fill_.CalibrationResult());
  ExpectRoundTrip<structloc_msgs::msg::WallFeaturePubSubType>(
      TestTopic("wall"), "structloc_msgs::msg::dds_::WallFeature_", fill_.WallFeature());
  ExpectRoundTrip<structloc_msgs::msg::PointFeaturePubSubType>(
      TestTopic("point_feature"), "structloc_msgs::msg::dds_::PointFeature_", fill_.PointFeature());
  ExpectRoundTrip<structloc_msgs::msg::StepTimingsPubSubType>(
      TestTopic("timings"), "structloc_msgs::msg::dds_::StepTimings_", fill_.StepTimings());
  ExpectRoundTrip<structloc_msgs::msg::FeatureSetPubSubType>(
      TestTopic("feature_set"), "structloc_msgs::msg::dds_::FeatureSet_",
      fill_.ScanFeatures().kinds()[1]);
  ExpectRoundTrip<structloc_msgs::msg::FeatureCountPubSubType>(
      TestTopic("feature_count"), "structloc_msgs::msg::dds_::FeatureCount_",
      fill_.LocalisationStatus().features()[2]);
  ExpectRoundTrip<structloc_msgs::msg::FeatureTimingPubSubType>(
      TestTopic("feature_timing"), "structloc_msgs::msg::dds_::FeatureTiming_",
      fill_.StepTimings().features()[0]);
  ExpectRoundTrip<structloc_msgs::msg::RobotParametersPubSubType>(
      TestTopic("robot_parameters"), "structloc_msgs::msg::dds_::RobotParameters_",
      fill_.RobotParameters());
}

}  // namespace
}  // namespace structloc
