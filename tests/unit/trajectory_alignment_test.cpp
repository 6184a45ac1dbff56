// One rigid alignment of a trajectory onto the truth (trajectory_alignment.hpp):
// a path in a frame of its own is brought back exactly, turned either way;
// what is not a rigid motion (a path bent on the way) stays as error; too
// few matched poses give no alignment. With a scale: a path scaled as well is
// brought back exactly, with the scale that undoes its own.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "structloc/replay/trajectory_alignment.hpp"
#include "structloc/replay/trajectory_error.hpp"

namespace structloc {
namespace {

using log_formats::StampedPose;

// A wavy tour: positions spread in both directions, headings along it.
std::vector<StampedPose> Tour() {
  std::vector<StampedPose> t;
  for (int i = 0; i < 200; ++i) {
    const double s = 0.1 * i;
    t.push_back({1000.0 + 0.1 * i, {s, 2.0 * std::sin(0.5 * s), 0.3 * std::cos(0.5 * s)}});
  }
  return t;
}

TEST(TrajectoryAlignment, APathInAFrameOfItsOwnIsBroughtBackExactly) {
  const auto truth = Tour();
  for (const double turn : {0.7, -0.7, 3.0, -3.0}) {
    const geometry::Pose2D frame{-4.0, 2.5, turn};
    const auto path = replay::Moved(truth, frame);
    const auto before = replay::CompareTrajectories(path, truth);
    EXPECT_GT(before.position_rmse_m, 1.0);
    const auto motion = replay::AlignTrajectory(path, truth);
    ASSERT_TRUE(motion) << turn;
    // The motion undoes the frame: motion * frame is the identity.
    const auto undone = geometry::Compose(*motion, frame);
    EXPECT_NEAR(undone.x, 0.0, 1e-9) << turn;
    EXPECT_NEAR(undone.y, 0.0, 1e-9) << turn;
    EXPECT_NEAR(undone.theta, 0.0, 1e-9) << turn;
    const auto after = replay::CompareTrajectories(replay::Moved(path, *motion), truth);
    EXPECT_EQ(after.matched, truth.size());
    EXPECT_LT(after.position_rmse_m, 1e-9) << turn;
    EXPECT_LT(after.heading_rmse_rad, 1e-9) << turn;
    const auto compared = replay::CompareAligned(path, truth);
    ASSERT_TRUE(compared) << turn;
    EXPECT_LT(compared->position_rmse_m, 1e-9) << turn;
  }
}

TEST(TrajectoryAlignment, WhatIsNotARigidMotionStaysAsError) {
  // A straight run whose second half the path puts 0.2 m to the side: the
  // best rigid motion turns the path so that the step is fitted by a line
  // (a turn is a sideways shift growing along the run), which leaves a
  // quarter of the step as RMSE, 0.05 m (to second order in the turn).
  std::vector<StampedPose> straight;
  for (int i = 0; i < 200; ++i) straight.push_back({1000.0 + 0.1 * i, {0.1 * i, 0.0, 0.0}});
  auto bent = straight;
  for (size_t i = bent.size() / 2; i < bent.size(); ++i) bent[i].pose.y += 0.2;
  const auto motion = replay::AlignTrajectory(bent, straight);
  ASSERT_TRUE(motion);
  const auto after = replay::CompareTrajectories(replay::Moved(bent, *motion), straight);
  EXPECT_NEAR(after.position_rmse_m, 0.05, 0.002);
  EXPECT_LT(replay::CompareTrajectories(bent, straight).position_rmse_m, 0.15);
  // Never worse than not aligning, on noisy, bent paths too.
  const auto truth = Tour();
  auto path = truth;
  for (size_t i = path.size() / 2; i < path.size(); ++i) path[i].pose.y += 0.2;
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (auto& p : path) p.pose.x += noise(rng);
  const auto noisy = replay::AlignTrajectory(path, truth);
  ASSERT_TRUE(noisy);
  EXPECT_LE(replay::CompareTrajectories(replay::Moved(path, *noisy), truth).position_rmse_m,
            replay::CompareTrajectories(path, truth).position_rmse_m);
}

TEST(TrajectoryAlignment, AScaledPathIsBroughtBackExactlyOnlyWithAScale) {
  const auto truth = Tour();
  for (const double scale : {0.99, 1.006}) {
    // The truth shrunk or stretched about the origin, in a frame of its own.
    const replay::Similarity frame{{-4.0, 2.5, 0.7}, scale};
    const auto path = replay::Moved(truth, frame);
    const auto rigid = replay::CompareAligned(path, truth);
    ASSERT_TRUE(rigid);
    EXPECT_GT(rigid->position_rmse_m, 0.01) << scale;  // a scale is no rigid motion
    const auto scaled = replay::CompareAlignedWithScale(path, truth);
    ASSERT_TRUE(scaled) << scale;
    EXPECT_NEAR(scaled->scale, 1.0 / scale, 1e-9);
    EXPECT_LT(scaled->error.position_rmse_m, 1e-9) << scale;
    EXPECT_LT(scaled->error.heading_rmse_rad, 1e-9) << scale;
    EXPECT_EQ(scaled->error.matched, truth.size());
  }
  // A path of the truth's own scale is given scale 1 and the rigid motion.
  const geometry::Pose2D motion{1.0, -2.0, -0.4};
  const auto moved = replay::Moved(truth, motion);
  const auto similarity = replay::AlignTrajectoryWithScale(moved, truth);
  const auto rigid = replay::AlignTrajectory(moved, truth);
  ASSERT_TRUE(similarity && rigid);
  EXPECT_NEAR(similarity->scale, 1.0, 1e-12);
  EXPECT_NEAR(similarity->motion.x, rigid->x, 1e-9);
  EXPECT_NEAR(similarity->motion.y, rigid->y, 1e-9);
  EXPECT_NEAR(similarity->motion.theta, rigid->theta, 1e-12);
  EXPECT_FALSE(replay::CompareAlignedWithScale({truth[3]}, truth));
}

TEST(TrajectoryAlignment, TooFewMatchedPosesGiveNoAlignment) {
  const auto truth = Tour();
  EXPECT_FALSE(replay::AlignTrajectory({}, truth));
  EXPECT_FALSE(replay::AlignTrajectory({truth[3]}, truth));
  EXPECT_FALSE(replay::CompareAligned({truth[3]}, truth));
  // Stamps the truth does not have (beyond the tolerance) do not match.
  auto late = truth;
  for (auto& p : late) p.stamp += 0.05;
  EXPECT_FALSE(replay::AlignTrajectory(late, truth));
  // Two poses at one place: the rotation about it is undetermined.
  std::vector<StampedPose> still{{1000.0, {1.0, 1.0, 0.0}}, {1000.1, {1.0, 1.0, 0.5}}};
  EXPECT_FALSE(replay::AlignTrajectory(still, truth));
}

}  // namespace
}  // namespace structloc
