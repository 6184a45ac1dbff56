// The localisation's health headline, decided in the core without DDS: a
// missing or silent input is WARN and, after silent_error_after_s, ERROR; a
// missing initial pose says how to give one; peer problems come first; the
// counters are always there.
#include <gtest/gtest.h>

#include <string>

#include "office_scene.hpp"
#include "structloc/localisation_core/tracking/session_health.hpp"

namespace structloc::localisation_core {
namespace {

const std::string kParams = std::string(STRUCTLOC_SOURCE_DIR) + "/maps/params/office_sick.xml";

class SessionHealthTest : public ::testing::Test {
 protected:
  HealthInputs Inputs(double now) const {
    HealthInputs in;
    in.now_s = now;
    in.started_s = 100.0;
    in.scan_topic = "rt/scan";
    in.odometry_topic = "rt/odom";
    in.initial_pose_topic = "rt/initialpose";
    return in;
  }
  bool HasValue(const SessionHealth& h, const std::string& key) const {
    for (const auto& kv : h.values) {
      if (kv.first == key) return true;
    }
    return false;
  }

  testing::OfficeScene office{4.71238898038469};
  SessionOptions options = LoadSessionOptions(kParams);
};

TEST_F(SessionHealthTest, NoOdometryYetIsAWarningThenAnError) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  const auto soon = AssessHealth(session, Inputs(100.0 + options.silent_error_after_s / 2));
  EXPECT_EQ(soon.level, HealthLevel::kWarn);
  EXPECT_NE(soon.message.find("no odometry on rt/odom yet"), std::string::npos) << soon.message;
  const auto late = AssessHealth(session, Inputs(100.0 + options.silent_error_after_s + 1));
  EXPECT_EQ(late.level, HealthLevel::kError) << late.message;
  EXPECT_TRUE(HasValue(late, "scans_processed"));
  EXPECT_TRUE(HasValue(late, "last_problem"));
}

TEST_F(SessionHealthTest, OdometryWithoutAnInitialPoseSaysHowToGiveOne) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  ASSERT_TRUE(session.AddOdometry(10.0, {0, 0, 0}, 100.0));
  auto in = Inputs(100.1);
  in.last_odometry_s = 100.0;
  const auto health = AssessHealth(session, in);
  EXPECT_EQ(health.level, HealthLevel::kWarn);
  EXPECT_NE(health.message.find("rt/initialpose"), std::string::npos) << health.message;
}

TEST_F(SessionHealthTest, SilentScansAfterTheTimeoutAreNamed) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  session.ExpectInitialPose(office.truth, TrackingSession::InitialPoseWhen::kAtFirstOdometry);
  ASSERT_TRUE(session.AddOdometry(10.0, {0, 0, 0}, 100.0));
  auto in = Inputs(100.0 + options.scan_timeout_s + 0.1);
  in.last_odometry_s = in.now_s;
  const auto health = AssessHealth(session, in);
  EXPECT_EQ(health.level, HealthLevel::kWarn);
  EXPECT_NE(health.message.find("no scans on rt/scan yet"), std::string::npos) << health.message;
}

TEST_F(SessionHealthTest, APeerProblemIsAnErrorAndComesFirst) {
  TrackingSession session(&office.world, office.options, options, Scheduling::kNewestWins);
  auto in = Inputs(100.1);
  in.peer_problems = {"incompatible QoS on rt/scan"};
  const auto health = AssessHealth(session, in);
  EXPECT_EQ(health.level, HealthLevel::kError);
  EXPECT_EQ(health.message, "incompatible QoS on rt/scan");
}

}  // namespace
}  // namespace structloc::localisation_core
