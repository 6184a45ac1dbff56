// EstimateScanLatency and OdometryBefore: a robot in a room with a cupboard
// swings its heading back and forth (up to 94 deg/s, as MIT CSAIL's B21 turns)
// while it creeps forward; each scan is taken `latency` before its stamp, and
// the log gives it the odometry at the stamp, sampled at 5 Hz like the scans.
// The estimate must find the latency from the scans and odometry alone, and
// apply none where there is none, nor where odometry's noise only seems to
// show one.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "structloc/slam_core/scan_latency.hpp"

namespace structloc::slam_core {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kPeriodS = 0.2;

struct Segment {
  Eigen::Vector2d a, b;
};

// A 10 x 6 m room with a cupboard off its centre (no symmetry to confuse ICP).
const std::vector<Segment>& Room() {
  static const std::vector<Segment> room = {
      {{-5, -3}, {5, -3}},      {{5, -3}, {5, 3}},      {{5, 3}, {-5, 3}},
      {{-5, 3}, {-5, -3}},      {{1.5, 1}, {2.5, 1}},   {{2.5, 1}, {2.5, 1.6}},
      {{2.5, 1.6}, {1.5, 1.6}}, {{1.5, 1.6}, {1.5, 1}},
  };
  return room;
}

geometry::Pose2D TruePose(double t) {
  return {-2.0 + 0.1 * t, -0.5, (60 * kPi / 180) * std::sin(2 * kPi * t / 4.0)};
}

// 181 beams over 180 deg, 5 mm range noise, in the laser's frame; beam k
// taken at `pose_of_beam(k)` (a laser sweeping while the robot turns), or
// all at `pose`.
template <class PoseOfBeam>
std::vector<Eigen::Vector2d> SweptScan(PoseOfBeam pose_of_beam, std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, 0.005);
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k <= 180; ++k) {
    const geometry::Pose2D pose = pose_of_beam(k);
    const double angle = pose.theta + (k - 90) * kPi / 180;
    const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
    double range = INFINITY;
    for (const auto& s : Room()) {
      const Eigen::Vector2d e = s.b - s.a;
      const double den = d.x() * e.y() - d.y() * e.x();
      if (std::abs(den) < 1e-12) continue;
      const Eigen::Vector2d w = s.a - pose.Translation();
      const double t = (w.x() * e.y() - w.y() * e.x()) / den;
      const double u = (w.x() * d.y() - w.y() * d.x()) / den;
      if (t > 0 && u >= 0 && u <= 1) range = std::min(range, t);
    }
    if (range > 15) continue;
    range += noise(random);
    points.push_back(
        {range * std::cos((k - 90) * kPi / 180), range * std::sin((k - 90) * kPi / 180)});
  }
  return points;
}

std::vector<Eigen::Vector2d> Scan(const geometry::Pose2D& pose, std::mt19937& random) {
  return SweptScan([&](int) { return pose; }, random);
}

struct Recording {
  std::vector<double> stamps;
  std::vector<geometry::Pose2D> odometry;
  std::vector<std::vector<Eigen::Vector2d>> points;
};

Recording Record(double latency_s) {
  std::mt19937 random(11);
  Recording r;
  for (int i = 0; i < 100; ++i) {
    const double stamp = 10.0 + kPeriodS * i;
    r.stamps.push_back(stamp);
    r.odometry.push_back(TruePose(stamp));
    r.points.push_back(Scan(TruePose(stamp - latency_s), random));
  }
  return r;
}

TEST(ScanLatency, FoundFromTheScansAndOdometry) {
  for (const double latency : {0.1237, -0.0581}) {
    const Recording r = Record(latency);
    const auto e = EstimateScanLatency(r.stamps, r.odometry, r.points);
    EXPECT_NEAR(e.latency_s, latency, 0.01);
    EXPECT_TRUE(e.Shown()) << "interval " << e.interval_low_s << " to " << e.interval_high_s;
    EXPECT_EQ(e.Applied(), e.latency_s);
    EXPECT_NEAR(e.interval_low_s, latency, 0.015);
    EXPECT_NEAR(e.interval_high_s, latency, 0.015);
    EXPECT_GT(e.pairs, 50u);
    EXPECT_LT(e.rms_at_estimate_rad, 0.5 * e.rms_at_zero_rad);
  }
}

TEST(ScanLatency, TheSameOnOneThreadOrSeveral) {
  const Recording r = Record(0.1237);
  const auto one = EstimateScanLatency(r.stamps, r.odometry, r.points, {}, {}, {}, 1);
  for (const int threads : {2, 5}) {
    const auto e = EstimateScanLatency(r.stamps, r.odometry, r.points, {}, {}, {}, threads);
    EXPECT_EQ(e.latency_s, one.latency_s) << threads << " threads";
    EXPECT_EQ(e.interval_low_s, one.interval_low_s);
    EXPECT_EQ(e.interval_high_s, one.interval_high_s);
    EXPECT_EQ(e.pairs, one.pairs);
    EXPECT_EQ(e.rms_at_estimate_rad, one.rms_at_estimate_rad);
  }
}

TEST(ScanLatency, NoneWhereThereIsNone) {
  const Recording r = Record(0.0);
  const auto e = EstimateScanLatency(r.stamps, r.odometry, r.points);
  EXPECT_NEAR(e.latency_s, 0.0, 0.01);
  EXPECT_FALSE(e.Shown()) << "interval " << e.interval_low_s << " to " << e.interval_high_s;
  EXPECT_EQ(e.Applied(), 0.0);
}

// Odometry whose heading errs by a degree at random at each sample (no
// latency): the errors pull the estimate off 0 by chance, and its interval
// must say that the recording does not show a latency.
TEST(ScanLatency, NoneAppliedWhereNoisyOdometryDoesNotShowOne) {
  Recording r = Record(0.0);
  std::mt19937 random(5);
  std::normal_distribution<double> heading_error(0.0, kPi / 180);
  for (auto& pose : r.odometry) pose.theta += heading_error(random);
  const auto e = EstimateScanLatency(r.stamps, r.odometry, r.points);
  EXPECT_LE(e.interval_low_s, 0.0);
  EXPECT_GE(e.interval_high_s, 0.0);
  EXPECT_FALSE(e.Shown());
  EXPECT_EQ(e.Applied(), 0.0) << "estimate " << e.latency_s;
}

// A laser whose 180 beams sweep over 0.1 s while the robot swings (one
// beam each 0.55 ms after the first): matched as they are, the scans tell the
// latency of their middle; given their beams' times, the estimate de-skews
// them and finds that of their first beam.
TEST(ScanLatency, ScansThatSweepAreDeskewedToTheirFirstBeam) {
  constexpr double kLatencyS = 0.1237, kBeamS = 0.1 / 180;
  std::mt19937 random(11);
  Recording r;
  PointTimes times;
  for (int i = 0; i < 100; ++i) {
    const double stamp = 10.0 + kPeriodS * i;
    r.stamps.push_back(stamp);
    r.odometry.push_back(TruePose(stamp));
    const double first = stamp - kLatencyS;
    r.points.push_back(SweptScan([&](int k) { return TruePose(first + k * kBeamS); }, random));
    auto& t = times.emplace_back();
    for (int k = 0; k <= 180; ++k) t.push_back(k * kBeamS);
  }
  const auto as_they_are = EstimateScanLatency(r.stamps, r.odometry, r.points);
  EXPECT_NEAR(as_they_are.latency_s, kLatencyS - 0.05, 0.02) << "the sweep's middle";
  const auto deskewed = EstimateScanLatency(r.stamps, r.odometry, r.points, {}, {}, times);
  EXPECT_NEAR(deskewed.latency_s, kLatencyS, 0.01);
  EXPECT_TRUE(deskewed.Shown());
  EXPECT_LT(deskewed.rms_at_estimate_rad, as_they_are.rms_at_estimate_rad);
}

TEST(ScanLatency, DeskewedPointsAreThoseOfTheFirstBeamsFrame) {
  // Turning at 1 rad/s about the laser: a point seen 0.1 s after the first
  // beam, straight ahead, lies 0.1 rad to the left in the first beam's frame.
  const std::vector<double> stamps = {0.0, 1.0};
  const std::vector<geometry::Pose2D> odometry = {{0, 0, 0}, {0, 0, 1.0}};
  const std::vector<std::vector<Eigen::Vector2d>> points = {{{2.0, 0.0}}, {{2.0, 0.0}}};
  const auto out = DeskewedPoints(stamps, odometry, points, {{0.1}, {0.0}}, 0.0);
  EXPECT_NEAR(out[0][0].x(), 2.0 * std::cos(0.1), 1e-12);
  EXPECT_NEAR(out[0][0].y(), 2.0 * std::sin(0.1), 1e-12);
  EXPECT_EQ(out[1][0], points[1][0]);
  EXPECT_EQ(DeskewedPoints(stamps, odometry, points, {}, 0.0)[0][0], points[0][0]) << "no times";
  EXPECT_THROW(DeskewedPoints(stamps, odometry, points, {{0.1, 0.2}, {0.0}}, 0.0),
               std::invalid_argument);
  // Stamps that do not increase (a recording's repeated stamp): the sample
  // is left out, the scans still de-skewed by the others.
  const std::vector<double> repeated = {0.0, 1.0, 1.0};
  const std::vector<geometry::Pose2D> three = {{0, 0, 0}, {0, 0, 1.0}, {0, 0, 5.0}};
  const auto kept = DeskewedPoints(repeated, three, {{{2.0, 0.0}}, {{2.0, 0.0}}, {{2.0, 0.0}}},
                                   {{0.1}, {0.0}, {0.0}}, 0.0);
  EXPECT_NEAR(kept[0][0].y(), 2.0 * std::sin(0.1), 1e-12);
}

TEST(ScanLatency, OdometryTakenEarlierAlongItsSteps) {
  const std::vector<double> stamps = {0.0, 1.0, 2.0};
  const std::vector<geometry::Pose2D> odometry = {{0, 0, 0}, {1, 0, 0.2}, {1, 2, 0.4}};
  const auto before = OdometryBefore(stamps, odometry, 0.25);
  EXPECT_NEAR(before[0].x, -0.25, 1e-12) << "beyond the start, along the first step";
  EXPECT_NEAR(before[0].theta, -0.05, 1e-12);
  EXPECT_NEAR(before[1].x, 0.75, 1e-12);
  EXPECT_NEAR(before[2].y, 1.5, 1e-12);
  EXPECT_NEAR(before[2].theta, 0.35, 1e-12);
  const auto after = OdometryBefore(stamps, odometry, -0.5);
  EXPECT_NEAR(after[2].y, 3.0, 1e-12) << "beyond the end, along the last step";
  EXPECT_EQ(OdometryBefore(stamps, odometry, 0.0)[1].theta, 0.2);
}

TEST(ScanLatency, OdometryThatStalledIsSpreadOverTheStall) {
  // Not updated from 1 to 3 s, then the whole motion at 4 s; and standing
  // still at the end.
  const std::vector<double> stamps = {0, 1, 2, 3, 4, 5, 6};
  const std::vector<geometry::Pose2D> odometry = {{0, 0, 0},    {0.1, 0, 0},   {0.1, 0, 0},
                                                  {0.1, 0, 0},  {0.5, 0, 0.8}, {0.5, 0, 0.8},
                                                  {0.5, 0, 0.8}};
  const auto before = OdometryBefore(stamps, odometry, 0.5);
  EXPECT_NEAR(before[4].x, 0.1 + 0.4 * 2.5 / 3, 1e-12) << "from the stall's first sample on";
  EXPECT_NEAR(before[4].theta, 0.8 * 2.5 / 3, 1e-12);
  EXPECT_NEAR(before[6].x, 0.5, 1e-12) << "standing still at the end";
  EXPECT_NEAR(before[6].theta, 0.8, 1e-12);
}

TEST(ScanLatency, StampsThatDoNotIncreaseAreNamed) {
  const std::vector<double> stamps = {0.0, 1.0, 1.0};
  const std::vector<geometry::Pose2D> odometry(3);
  EXPECT_NO_THROW(OdometryBefore(stamps, odometry, 0.0)) << "no latency, no need";
  try {
    OdometryBefore(stamps, odometry, 0.1);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scan 2's stamp"), std::string::npos) << e.what();
  }
  EXPECT_THROW(OdometryBefore({0.0, 1.0}, odometry, 0.1), std::invalid_argument);
}

TEST(ScanLatency, ALogWithoutTurnsDoesNotTellIt) {
  Recording r = Record(0.1);
  for (auto& pose : r.odometry) pose = {};
  const auto e = EstimateScanLatency(r.stamps, r.odometry, r.points);
  EXPECT_EQ(e.pairs, 0u);
  EXPECT_FALSE(e.Shown());
  EXPECT_EQ(e.Applied(), 0.0);
  EXPECT_NE(e.untold.find("no turn"), std::string::npos) << e.untold;
}

TEST(ScanLatency, StampsThatDoNotIncreaseTellNone) {
  Recording r = Record(0.1);
  r.stamps[40] = r.stamps[39];
  const auto e = EstimateScanLatency(r.stamps, r.odometry, r.points);
  EXPECT_FALSE(e.Shown());
  EXPECT_EQ(e.Applied(), 0.0);
  EXPECT_NE(e.untold.find("scan 40's stamp"), std::string::npos) << e.untold;
}

TEST(ScanLatency, OptionsOutOfRangeAreRefused) {
  const Recording r = Record(0.0);
  ScanLatencyOptions options;
  options.confidence = 1.0;
  EXPECT_THROW(EstimateScanLatency(r.stamps, r.odometry, r.points, options), std::invalid_argument);
  options = {};
  options.block_pairs = 0;
  EXPECT_THROW(EstimateScanLatency(r.stamps, r.odometry, r.points, options), std::invalid_argument);
}

}  // namespace
}  // namespace structloc::slam_core
