// The calibration component's message conversions, without a participant:
// wheel encoders of both drive kinds as the simulator publishes them come back
// as the core's samples, and a result carries the estimated parameters' names,
// their covariance row-major, its window and the flagged changes.
#include <gtest/gtest.h>

#include "structloc/calibration/calibration_conversions.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/simulator/sim_conversions.hpp"

namespace structloc {
namespace {

namespace cc = calibration_core;

TEST(CalibrationConversions, WheelEncodersOfBothDriveKindsBecomeSamples) {
  simulation_core::SimState state;
  state.time = 2.5;
  state.traction_ticks = 4294967290u;
  state.steering_ticks = -17;
  state.left_ticks = 4294967295u;
  state.right_ticks = 12;
  kinematics::RobotParameters tricycle;
  const auto t = calibration::FromWheelEncoders(
      simulator::ToWheelEncoders(state, tricycle, 4294967280u, 100.0));
  EXPECT_DOUBLE_EQ(t.t, 102.5);
  EXPECT_EQ(t.traction_ticks, 4294967290u);
  EXPECT_EQ(t.steering_ticks, -17.0);
  EXPECT_EQ(t.left_ticks, 0u);
  kinematics::RobotParameters differential;
  differential.kind = kinematics::DriveKind::kDifferential;
  const auto m = simulator::ToWheelEncoders(state, differential, 0, 100.0);
  EXPECT_TRUE(m.differential());
  EXPECT_EQ(m.traction_ticks(), 0u);
  const auto d = calibration::FromWheelEncoders(m);
  EXPECT_EQ(d.left_ticks, 4294967295u);
  EXPECT_EQ(d.right_ticks, 12u);
  EXPECT_EQ(d.traction_ticks, 0u);
}

TEST(CalibrationConversions, ResultCarriesCovarianceWindowAndChanges) {
  cc::OnlineEstimate e;
  e.report.success = true;
  e.report.parameters.kind = kinematics::DriveKind::kDifferential;
  e.report.parameters.right_wheel_radius = 0.101;
  e.report.estimated[cc::kLeftWheelRadius] = e.report.estimated[cc::kRightWheelRadius] = true;
  e.report.standard_deviation[cc::kRightWheelRadius] = 2e-5;
  e.report.covariance.resize(2, 2);
  e.report.covariance << 1e-10, 2e-11, 2e-11, 4e-10;
  e.window_start_s = 10.0;
  e.window_end_s = 70.25;
  e.changes.push_back({cc::kRightWheelRadius, 0.1, 0.101, 35.4});
  const auto msg = calibration::ToCalibrationResult(e);
  EXPECT_TRUE(msg.parameters().differential());
  EXPECT_DOUBLE_EQ(msg.parameters().right_wheel_radius_m(), 0.101);
  EXPECT_DOUBLE_EQ(msg.standard_deviations().right_wheel_radius_m(), 2e-5);
  ASSERT_EQ(msg.estimated().size(), 2u);
  EXPECT_EQ(msg.estimated()[0], "left_wheel_radius");
  EXPECT_EQ(msg.estimated()[1], "right_wheel_radius");
  ASSERT_EQ(msg.covariance().size(), 4u);
  EXPECT_DOUBLE_EQ(msg.covariance()[1], 2e-11);
  EXPECT_DOUBLE_EQ(msg.covariance()[3], 4e-10);
  EXPECT_DOUBLE_EQ(dds_common::FromRosTime(msg.window_start()), 10.0);
  EXPECT_DOUBLE_EQ(dds_common::FromRosTime(msg.window_end()), 70.25);
  EXPECT_DOUBLE_EQ(dds_common::FromRosTime(msg.header().stamp()), 70.25);
  ASSERT_EQ(msg.changed().size(), 1u);
  EXPECT_EQ(msg.changed()[0], "right_wheel_radius 0.1 -> 0.101 m (+1.00 %, 35.4 sigma)");
}

}  // namespace
}  // namespace structloc
