// Each pipeline step on analytic cases: prefilter counts, a window on a known
// line gives its (r, alpha) to 1e-9, known lines intersect where expected,
// points on a known circle give centre and radius, and every solver recovers
// a known pose exactly from noise-free features.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "structloc/localisation_core/features/corners/corner_extraction.hpp"
#include "structloc/localisation_core/features/cylinders/cylinder_extraction.hpp"
#include "structloc/localisation_core/scan/deskew.hpp"
#include "structloc/localisation_core/scan/line_fit.hpp"
#include "structloc/localisation_core/scan/prefilter.hpp"
#include "structloc/localisation_core/solver/pose_solver.hpp"

namespace structloc::localisation_core {
namespace {

using geometry::kPi;

ScanView View(const std::vector<float>& ranges, double angle_min, double inc) {
  ScanView v;
  v.ranges = ranges.data();
  v.count = ranges.size();
  v.angle_min = angle_min;
  v.angle_increment = inc;
  v.range_max = 100.0;
  return v;
}

TEST(Prefilter, RejectsAndCountsSpecialValuesAndRangeGate) {
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> r = {1.0f, std::nanf(""), inf, -inf, -1.0f, 0.2f, 5.0f, 1.0f};
  const auto view = View(r, 0.0, 0.01);
  BeamDirections dirs;
  dirs.Update(view);
  ScanPoints pts;
  PrefilterStats stats;
  PrefilterOptions o;  // 0.5 .. 4 m
  RangeGate(view, dirs, o, pts, stats);
  EXPECT_EQ(stats.beams, 8u);
  EXPECT_EQ(stats.non_finite, 3u);
  EXPECT_EQ(stats.negative, 1u);
  EXPECT_EQ(stats.out_of_range, 2u);
  ASSERT_EQ(pts.Size(), 2u);
  EXPECT_EQ(pts.beam[1], 7);
  for (size_t i = 0; i < pts.Size(); ++i) EXPECT_TRUE(std::isfinite(pts.x[i] + pts.y[i]));
}

TEST(Prefilter, DropsUnsupportedPointsAndThinsAndWrapsOnlyFullScans) {
  ScanPoints pts;
  pts.wraps = false;
  // A line of points 2 cm apart with one isolated point in the middle.
  for (int i = 0; i < 10; ++i) pts.Push(1.0, 0.02 * i, i);
  pts.x[5] = 2.0;
  PrefilterStats stats;
  PrefilterOptions o;
  RejectUnsupportedAndThin(o, pts, stats);
  EXPECT_EQ(stats.unsupported, 1u);
  // 6 cm thinning of the nine left, 2 cm apart, keeps every third point.
  EXPECT_EQ(stats.kept, pts.Size());
  EXPECT_EQ(stats.unsupported + stats.thinned + stats.kept, 10u);
  EXPECT_EQ(pts.Size(), 4u);  // y = 0, 0.06, 0.12, 0.18
  // The first point's only close neighbour is the last point: kept in a full
  // (wrapping) scan, unsupported in an open one.
  for (bool wraps : {true, false}) {
    ScanPoints ring;
    ring.wraps = wraps;
    ring.Push(1.0, 0.0, 0);
    for (int i = 1; i < 9; ++i) ring.Push(3.0, 0.1 * i, i);
    ring.Push(1.0, -0.05, 9);
    PrefilterStats ring_stats;
    RejectUnsupportedAndThin(o, ring, ring_stats);
    EXPECT_EQ(ring_stats.unsupported, wraps ? 0u : 2u) << wraps;
  }
}

TEST(LineFit, WindowOnAKnownLineGivesItsRAlphaTo1e9) {
  for (double alpha : {-3.0, -1.2, 0.0, 0.7, kPi / 2, 2.9}) {
    const double r = 2.37;
    ScanPoints pts;
    const Eigen::Vector2d n(std::cos(alpha), std::sin(alpha)), d(-n.y(), n.x());
    for (int k = 0; k < 7; ++k) {
      const Eigen::Vector2d p = r * n + (0.05 * k - 0.1) * d;
      pts.Push(p.x(), p.y(), k);
    }
    std::vector<WindowLine> lines;
    FitWindowLines(pts, LineFitOptions{}, lines);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_TRUE(lines[0].valid);
    EXPECT_NEAR(lines[0].line.r, r, 1e-9);
    EXPECT_NEAR(geometry::WrapAngle(lines[0].line.Alpha() - alpha), 0.0, 1e-9) << alpha;
    EXPECT_NEAR(lines[0].line.sse, 0.0, 1e-12);
  }
}

TEST(LineFit, SlidingSumsMatchFreshFitsOverALongWrappingScan) {
  ScanPoints pts;
  pts.wraps = true;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 0.01);
  for (int i = 0; i < 1081; ++i) {
    const double a = 2 * kPi * i / 1081.0;
    const double range = 3.0 + std::sin(3 * a) + noise(rng);
    pts.Push(range * std::cos(a), range * std::sin(a), i);
  }
  std::vector<WindowLine> lines;
  FitWindowLines(pts, LineFitOptions{}, lines);
  ASSERT_EQ(lines.size(), 1081u);
  for (size_t i : {0u, 500u, 1076u, 1080u}) {
    LineSums fresh;
    for (int k = 0; k < 7; ++k) fresh.Add(pts.x[(i + k) % 1081], pts.y[(i + k) % 1081]);
    const auto e = FitLine(fresh, 0.0, 0.0);
    EXPECT_NEAR(lines[i].line.r, e.r, 1e-9);
    EXPECT_NEAR(lines[i].line.cos_alpha, e.cos_alpha, 1e-9);
    EXPECT_NEAR(lines[i].line.sin_alpha, e.sin_alpha, 1e-9);
  }
}

TEST(Corners, TwoKnownLinesIntersectWhereExpected) {
  // Points along x = 2 (y from -1 to -0.1) then along y = 0.5... an L-shaped corner at (2, 0).
  ScanPoints pts;
  for (int k = 0; k < 20; ++k) pts.Push(2.0, -1.0 + 0.05 * k, k);
  for (int k = 0; k < 20; ++k) pts.Push(2.0 - 0.05 * k, 0.0, 20 + k);
  std::vector<WindowLine> lines;
  LineFitOptions tight;
  tight.max_rms_m = 1e-6;
  FitWindowLines(pts, tight, lines);
  const std::vector<ExpectedPoint> expected{{0, 7, {0, 0}, {2.0, 0.0}, 0.0}};
  CornerWork work;
  std::vector<PointCluster> out;
  ExtractCorners(lines, false, expected, CornerOptions{}, 7, work, out);
  // Windows straddling the corner are excluded by the rms check (tight here).
  ASSERT_EQ(out.size(), 1u);
  EXPECT_GE(out[0].members, 5);
  EXPECT_NEAR(out[0].mean.x(), 2.0, 1e-9);
  EXPECT_NEAR(out[0].mean.y(), 0.0, 1e-9);
}

TEST(Cylinders, PointsOnAKnownCircleGiveCentreAndRadius) {
  ScanPoints pts;
  const Eigen::Vector2d c(3.0, -1.0);
  for (int k = 0; k < 7; ++k) {
    const double a = 2.6 + 0.15 * k;
    pts.Push(c.x() + 0.3 * std::cos(a), c.y() + 0.3 * std::sin(a), k);
  }
  const auto fit = FitCircle(pts, 0, 7);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.xc, c.x(), 1e-9);
  EXPECT_NEAR(fit.yc, c.y(), 1e-9);
  EXPECT_NEAR(fit.radius, 0.3, 1e-9);
  EXPECT_GT(fit.quality, 1e12);
}

TEST(Deskew, LinearMotionMovesBeamsIntoTheFirstBeamFrame) {
  BeamMotion motion;
  LinearBeamMotion({0.1, 0.0, 0.2}, 11, motion);
  EXPECT_NEAR(motion.x[10], 0.1, 1e-12);
  EXPECT_NEAR(std::atan2(motion.s[10], motion.c[10]), 0.2, 1e-12);
  EXPECT_NEAR(std::atan2(motion.s[5], motion.c[5]), 0.1, 1e-12);
  ScanPoints pts;
  pts.Push(1.0, 0.0, 10);
  Deskew(motion, pts);
  EXPECT_NEAR(pts.x[0], 0.1 + std::cos(0.2), 1e-12);
  EXPECT_NEAR(pts.y[0], std::sin(0.2), 1e-12);
}

TEST(Deskew, BeamMotionFromAnOdometryHistoryMatchesTheAnalyticMotion) {
  // Base drives at 1 m/s along x while turning at 0.5 rad/s; odometry at 100 Hz.
  OdometryHistory history;
  auto base_at = [](double t) {
    const double w = 0.5, v = 1.0;  // exact arc
    return geometry::Pose2D{v / w * std::sin(w * t), v / w * (1 - std::cos(w * t)), w * t};
  };
  for (int k = 0; k <= 100; ++k) history.Add(0.01 * k, base_at(0.01 * k));
  const geometry::Pose2D mount{0.2, 0.05, 0.1};
  BeamMotion motion;
  ASSERT_TRUE(BeamMotionFromHistory(history, mount, 0.3, 1e-4, 1000, motion));
  const geometry::Pose2D ref = geometry::Compose(base_at(0.3), mount);
  for (size_t i : {0u, 499u, 999u}) {
    const geometry::Pose2D truth =
        geometry::Between(ref, geometry::Compose(base_at(0.3 + 1e-4 * i), mount));
    EXPECT_NEAR(motion.x[i], truth.x, 1e-5) << i;
    EXPECT_NEAR(motion.y[i], truth.y, 1e-5) << i;
    EXPECT_NEAR(std::atan2(motion.s[i], motion.c[i]), truth.theta, 1e-9) << i;
  }
  EXPECT_FALSE(BeamMotionFromHistory(history, mount, 0.95, 1e-4, 1000, motion));  // past the end
}

TEST(OdometryHistory, InterpolatesAndRefusesOutOfOrderAndNonFinite) {
  OdometryHistory h(4);
  EXPECT_EQ(h.Add(1.0, {0, 0, 3.0}), OdometryHistory::AddResult::kAdded);
  EXPECT_EQ(h.Add(2.0, {1, 2, -3.0}), OdometryHistory::AddResult::kAdded);
  EXPECT_EQ(h.Add(1.5, {0, 0, 0}), OdometryHistory::AddResult::kOutOfOrder);
  EXPECT_EQ(h.Add(3.0, {NAN, 0, 0}), OdometryHistory::AddResult::kNonFinite);
  const auto mid = h.At(1.5);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR(mid->x, 0.5, 1e-12);
  EXPECT_NEAR(mid->y, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(mid->theta), kPi, 1e-9);  // the short way across +-pi
  EXPECT_FALSE(h.At(0.5).has_value());
  for (int i = 0; i < 5; ++i) h.Add(3.0 + i, {0, 0, 0});  // capacity 4: oldest dropped
  EXPECT_EQ(h.Size(), 4u);
  EXPECT_DOUBLE_EQ(h.Oldest(), 4.0);
}

// Noise-free features of a known pose in a known world.
struct Scene {
  geometry::Pose2D truth{1.3, -0.4, 0.37};
  std::vector<WallMeasurement> walls;
  std::vector<PointMeasurement> points;
  Scene() {
    for (auto [r, a] : {std::pair{3.0, 0.2}, {2.0, 1.9}, {4.0, -2.0}}) {
      WallMeasurement m;
      m.world_r = r;
      m.world_alpha = a;
      m.r = r - (truth.x * std::cos(a) + truth.y * std::sin(a));
      m.alpha = geometry::WrapAngle(a - truth.theta);
      m.covariance = Eigen::Vector2d(1e-4, 1e-4).asDiagonal();
      walls.push_back(m);
    }
    PointMeasurement corner;
    corner.world = {4.0, 2.5};
    corner.sensor = truth.ApplyInverse(corner.world);
    corner.covariance = 1e-4 * Eigen::Matrix2d::Identity();
    points.push_back(corner);
    PointMeasurement pillar = corner;
    pillar.world = {-1.0, 1.0};
    pillar.sensor = truth.ApplyInverse(pillar.world);
    pillar.bisection = BisectionTerm::kDistance;
    points.push_back(pillar);
  }
};

TEST(PoseSolvers, RecoverAKnownPoseExactlyFromNoiseFreeFeatures) {
  Scene s;
  SolveInput in;
  in.walls = &s.walls;
  in.points = &s.points;
  in.prior = {s.truth.x + 0.12, s.truth.y - 0.08, s.truth.theta + 0.05};
  in.prior_covariance = Eigen::Vector3d(1e8, 1e8, 1e8).asDiagonal();  // a prior with no pull
  SolveOutput out;
  SolverOptions o;
  SolveWeighted(in, o, out);
  EXPECT_NEAR(out.pose.x, s.truth.x, 1e-6);
  EXPECT_NEAR(out.pose.y, s.truth.y, 1e-6);
  EXPECT_NEAR(out.pose.theta, s.truth.theta, 1e-7);
  // The thesis' linear solver: walls and corners, odometry not needed (no prior pull).
  SolveThesisLinear(in, o, out);
  EXPECT_NEAR(out.pose.x, s.truth.x, 1e-9);
  EXPECT_NEAR(out.pose.y, s.truth.y, 1e-9);
  EXPECT_NEAR(out.pose.theta, s.truth.theta, 1e-12);
  // Bisection includes the odometry point with equal weight: exact only with the prior at truth.
  in.prior = {s.truth.x, s.truth.y, s.truth.theta + 0.05};
  o.bisection_iterations = 30;
  SolveBisection(in, o, out);
  EXPECT_NEAR(out.pose.x, s.truth.x, 1e-6);
  EXPECT_NEAR(out.pose.y, s.truth.y, 1e-6);
}

TEST(PoseSolvers, WeightedSolverDropsAGrossOutlier) {
  Scene s;
  s.walls[1].r += 0.15;  // a wall matched to the wrong surface
  SolveInput in;
  in.walls = &s.walls;
  in.points = &s.points;
  in.prior = s.truth;
  in.prior_covariance = Eigen::Vector3d(0.01, 0.01, 0.01).asDiagonal();
  SolveOutput out;
  SolveWeighted(in, SolverOptions{}, out);
  EXPECT_FALSE(out.wall_used[1]);
  EXPECT_NEAR(out.pose.x, s.truth.x, 1e-6);
  EXPECT_NEAR(out.pose.y, s.truth.y, 1e-6);
}

}  // namespace
}  // namespace structloc::localisation_core
