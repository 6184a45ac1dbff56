// Odometry re-synthesised from known poses (structloc synthesise-odometry):
// zero errors give the poses back, each systematic error has the size it is
// given, noise is seeded, and the command turns a corrected log into an
// evaluation log and a ground-truth file, with a laser stamped late if asked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "cli_runner.hpp"
#include "structloc/simulation_core/odometry_errors.hpp"
#include "temp_dir.hpp"

namespace structloc::simulation_core {
namespace {

using geometry::kPi;
using geometry::Pose2D;

// A 10 m straight drive along x in 0.1 m steps, then a quarter turn on the spot.
std::vector<Pose2D> Drive() {
  std::vector<Pose2D> poses;
  for (int i = 0; i <= 100; ++i) poses.push_back({0.1 * i, 0.0, 0.0});
  for (int i = 1; i <= 10; ++i) poses.push_back({10.0, 0.0, 0.05 * kPi * i});
  return poses;
}

Pose2D Synthesise(const OdometryErrorModel& model, uint32_t seed) {
  std::mt19937 rng(seed);
  const auto poses = Drive();
  OdometrySynthesiser odometry(model, rng, poses.front());
  Pose2D last;
  for (size_t i = 1; i < poses.size(); ++i) last = odometry.Next(poses[i]);
  return last;
}

TEST(OdometrySynthesis, WithoutErrorsTheKnownPosesComeBack) {
  const Pose2D end = Synthesise({}, 1);
  EXPECT_NEAR(end.x, 10.0, 1e-9);
  EXPECT_NEAR(end.y, 0.0, 1e-9);
  EXPECT_NEAR(end.theta, kPi / 2, 1e-9);
}

TEST(OdometrySynthesis, ScaleErrorAndHeadingDriftHaveTheirGivenSize) {
  OdometryErrorModel scale;
  scale.scale_error = 0.015;
  EXPECT_NEAR(Synthesise(scale, 1).x, 10.15, 1e-9);

  OdometryErrorModel drift;
  drift.heading_drift_rad_per_m = 0.3 * kPi / 180.0;
  const Pose2D end = Synthesise(drift, 1);
  // 3 deg over 10 m, accumulated linearly: the path bends by half of that on average.
  EXPECT_NEAR(end.theta, kPi / 2 + 10.0 * drift.heading_drift_rad_per_m, 1e-9);
  EXPECT_NEAR(end.y, 10.0 * std::sin(1.5 * kPi / 180.0), 0.01);
}

TEST(OdometrySynthesis, NoiseIsSeededAndGrowsWithTheDistance) {
  OdometryErrorModel noise;
  noise.noise_xy_m_per_sqrt_m = 0.01;
  const Pose2D a = Synthesise(noise, 7), b = Synthesise(noise, 7), c = Synthesise(noise, 8);
  EXPECT_EQ(a.x, b.x);
  EXPECT_NE(a.x, c.x);
  // 100 steps of 0.1 m: sigma 0.01 * sqrt(0.1) per step and axis, 0.01 * sqrt(10) in all.
  double sum2 = 0.0;
  for (uint32_t seed = 1; seed <= 200; ++seed)
    sum2 += std::pow(Synthesise(noise, seed).x - 10.0, 2);
  EXPECT_NEAR(std::sqrt(sum2 / 200.0), 0.01 * std::sqrt(10.0), 0.01);
  noise.noise_xy_m_per_sqrt_m = -1.0;
  EXPECT_THROW(Synthesise(noise, 1), std::invalid_argument);
}

TEST(OdometrySynthesis, TurnErrorsGrowWithTheTurnNotTheDistance) {
  OdometryErrorModel scale;
  scale.turn_scale_error = 0.02;
  const Pose2D turned = Synthesise(scale, 1);
  EXPECT_NEAR(turned.theta, 1.02 * kPi / 2, 1e-9);
  EXPECT_NEAR(turned.x, 10.0, 1e-9) << "the straight drive has no turn to scale";
  EXPECT_NEAR(turned.y, 0.0, 1e-9);

  OdometryErrorModel slip;
  slip.noise_theta_rad_per_sqrt_rad = 3.0 * kPi / 180.0;
  EXPECT_EQ(Synthesise(slip, 7).theta, Synthesise(slip, 7).theta);
  // Ten turns of pi/20: sigma 3 deg * sqrt(pi/2) over the quarter turn, nothing
  // on the straight.
  double sum2 = 0.0;
  for (uint32_t seed = 1; seed <= 400; ++seed) {
    const Pose2D end = Synthesise(slip, seed);
    EXPECT_NEAR(end.y, 0.0, 1e-9);
    sum2 += std::pow(end.theta - kPi / 2, 2);
  }
  EXPECT_NEAR(std::sqrt(sum2 / 400.0), slip.noise_theta_rad_per_sqrt_rad * std::sqrt(kPi / 2),
              0.1 * slip.noise_theta_rad_per_sqrt_rad * std::sqrt(kPi / 2));
  slip.turn_scale_error = -1.0;
  EXPECT_THROW(Synthesise(slip, 1), std::invalid_argument);
}

TEST(OdometrySynthesis, RestampingRespectsSpeedTurnRateAndMinimumStep) {
  EXPECT_DOUBLE_EQ(RestampedTime(1.0, {0, 0, 0}, {1.0, 0, 0}, 0.5, 0.5, 0.1), 3.0);
  EXPECT_DOUBLE_EQ(RestampedTime(1.0, {0, 0, 0}, {0, 0, 1.0}, 0.5, 0.5, 0.1), 3.0);
  EXPECT_DOUBLE_EQ(RestampedTime(1.0, {0, 0, 0}, {0, 0, 0}, 0.5, 0.5, 0.1), 1.1);
}

// A corrected log of five scans 0.1 m and 1 s apart along x.
std::string CorrectedDrive(const testing::TempDir& dir) {
  std::ostringstream log;
  for (int i = 0; i < 5; ++i) {
    log << "FLASER 3 1.0 1.5 2.0 " << 0.1 * i << " 0 0 " << 0.1 * i << " 0 0 " << i << ".0 host "
        << i << ".0\n";
  }
  return dir.Write("corrected.log", log.str());
}

TEST(SynthesiseOdometryCommand, WritesAnEvaluationLogAndTheTruth) {
  const testing::TempDir dir;
  const auto in = CorrectedDrive(dir);
  auto r = testing::RunCli({"synthesise-odometry", "--log", in, "--out", dir / "eval.log",
                            "--truth", dir / "truth.tum", "--scale-error", "0.1"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string eval = testing::ReadFile(dir / "eval.log");
  EXPECT_EQ(std::count(eval.begin(), eval.end(), '\n'), 14);  // 4 comments + 5 x (ODOM, laser)
  EXPECT_NE(eval.find("ODOM 0.440000 0.000000"), std::string::npos) << eval;
  const std::string truth = testing::ReadFile(dir / "truth.tum");
  EXPECT_NE(truth.find("4.000000 0.400000 0.000000"), std::string::npos) << truth;

  r = testing::RunCli({"synthesise-odometry", "--log", dir.Write("empty.log", "# nothing\n"),
                       "--out", dir / "e.log", "--truth", dir / "e.tum"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no laser scan with a pose"), std::string::npos) << r.output;
  EXPECT_FALSE(std::ifstream(dir / "e.log").good());
}

// A laser stamped late: each scan written at its stamp plus the latency, with
// the odometry of that moment; the truth keeps the scan's pose at the new stamp.
TEST(SynthesiseOdometryCommand, WritesALaserStampedLate) {
  const testing::TempDir dir;
  const auto in = CorrectedDrive(dir);
  auto r = testing::RunCli({"synthesise-odometry", "--log", in, "--out", dir / "eval.log",
                            "--truth", dir / "truth.tum", "--scan-latency", "0.25"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string eval = testing::ReadFile(dir / "eval.log");
  EXPECT_NE(eval.find("ODOM 0.125000 0.000000 0.000000 0.000000 0.000000 0 1.250000"),
            std::string::npos)
      << eval;
  EXPECT_NE(eval.find("ODOM 0.425000"), std::string::npos) << "along the last step\n" << eval;
  const std::string truth = testing::ReadFile(dir / "truth.tum");
  EXPECT_NE(truth.find("1.250000 0.100000 0.000000"), std::string::npos) << truth;

  std::ostringstream same;
  for (int i = 0; i < 3; ++i) same << "FLASER 3 1.0 1.5 2.0 0 0 0 0 0 0 7.0 host 7.0\n";
  r = testing::RunCli({"synthesise-odometry", "--log", dir.Write("same.log", same.str()), "--out",
                       dir / "s.log", "--truth", dir / "s.tum", "--scan-latency", "0.1"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--restamp"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace structloc::simulation_core
