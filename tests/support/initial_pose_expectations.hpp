// Test helper: the checks a pose found by a search (global start, pose-hint
// check) must pass against the robot's true pose, shared by their tests.
#pragma once

#include <gtest/gtest.h>

#include "structloc/localisation_core/tracking/session_inbox.hpp"

namespace structloc::testing {

// `found` is the robot's pose at `stamp`, within 5 cm and 0.03 rad of `truth`,
// with the covariance the search was given.
inline void ExpectFoundAt(const localisation_core::InitialPoseInput& found, double stamp,
                          const geometry::Pose2D& truth, const Eigen::Matrix3d& covariance) {
  EXPECT_DOUBLE_EQ(found.stamp, stamp);
  EXPECT_NEAR(found.pose.x, truth.x, 0.05);
  EXPECT_NEAR(found.pose.y, truth.y, 0.05);
  EXPECT_NEAR(found.pose.theta, truth.theta, 0.03);
  EXPECT_EQ(found.covariance, covariance);
}

}  // namespace structloc::testing
