// RecentScans (recent_scans.hpp): the scans a robot without a pose took on
// its last metres come back in the newest scan's frame, each point with the
// place it was seen from, spaced and bounded as the options say; and in a
// room whose half-turned twin fits one scan of a 180 deg laser as well, the
// scans taken on the way there (through a door from a corridor), placed by
// odometry with a scale error and heading drift, make the search find the
// robot; not from the earlier scans alone, and not from readings that do not
// fit together.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "structloc/localisation_core/global/global_localiser.hpp"
#include "structloc/localisation_core/global/recent_scans.hpp"
#include "synthetic_scans.hpp"

namespace structloc::localisation_core {
namespace {

// The world point (3, 1) as seen by a laser at `pose`.
std::vector<Eigen::Vector2d> SeenFrom(const geometry::Pose2D& pose) {
  return {pose.ApplyInverse(Eigen::Vector2d(3.0, 1.0))};
}

TEST(RecentScans, GivesEarlierScansInTheNewestFrameWithWhereTheyWereSeenFrom) {
  RecentScans recent;
  EXPECT_TRUE(recent.InNewestFrame().points.empty());
  EXPECT_EQ(recent.Scans(), 0u);
  const geometry::Pose2D poses[] = {{0.0, 0.0, 0.0}, {0.5, 0.0, 0.2}, {1.0, 0.3, 0.5}};
  for (const auto& pose : poses) recent.Add(SeenFrom(pose), pose);
  ASSERT_EQ(recent.Scans(), 3u);
  const Readings readings = recent.InNewestFrame();
  ASSERT_EQ(readings.points.size(), 3u);
  ASSERT_EQ(readings.seen_from.size(), 3u);
  const Eigen::Vector2d point = poses[2].ApplyInverse(Eigen::Vector2d(3.0, 1.0));
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR((readings.points[i] - point).norm(), 0.0, 1e-12) << i;
    const Eigen::Vector2d from = poses[2].ApplyInverse(poses[2 - i].Translation());
    EXPECT_NEAR((readings.seen_from[i] - from).norm(), 0.0, 1e-12) << i;
  }
}

TEST(RecentScans, KeepsScansApartAndWithinTheCountAndPath) {
  RecentScansOptions options;
  options.max_scans = 4;
  options.max_travel_m = 10.0;
  RecentScans recent(options);
  // Standing still: one scan, however many come.
  for (int i = 0; i < 5; ++i) recent.Add(SeenFrom({0, 0, 0}), {0, 0, 0});
  EXPECT_EQ(recent.Scans(), 1u);
  // A turn on the spot counts as apart.
  recent.Add(SeenFrom({0, 0, 0.5}), {0, 0, 0.5});
  EXPECT_EQ(recent.Scans(), 2u);
  // Steps of an eighth of a metre with scans kept a quarter apart: every
  // second one is kept, never more than max_scans.
  options.min_spacing_m = 0.25;
  RecentScans moving(options);
  for (int i = 1; i <= 30; ++i) moving.Add(SeenFrom({0.125 * i, 0, 0}), {0.125 * i, 0, 0});
  EXPECT_EQ(moving.Scans(), 4u);
  // The path limit: 1 m of scans 0.5 m apart keeps three of them.
  options.max_scans = 100;
  options.max_travel_m = 1.0;
  RecentScans short_path(options);
  for (int i = 0; i <= 10; ++i) short_path.Add(SeenFrom({0.5 * i, 0, 0}), {0.5 * i, 0, 0});
  EXPECT_EQ(short_path.Scans(), 3u);
  short_path.Clear();
  EXPECT_EQ(short_path.Scans(), 0u);
  // max_scans 1: the newest alone.
  options.max_scans = 1;
  RecentScans newest_only(options);
  for (int i = 0; i <= 10; ++i) newest_only.Add(SeenFrom({0.5 * i, 0, 0}), {0.5 * i, 0, 0});
  EXPECT_EQ(newest_only.Scans(), 1u);
}

TEST(RecentScans, LeavesOutNonFiniteScansAndRefusesBadOptions) {
  RecentScans recent;
  EXPECT_FALSE(recent.Add(SeenFrom({0, 0, 0}), {NAN, 0, 0}));
  EXPECT_EQ(recent.Scans(), 0u);
  EXPECT_TRUE(recent.Add({{1.0, 0.0}, {INFINITY, 0.0}}, {0, 0, 0}));
  EXPECT_EQ(recent.InNewestFrame().points.size(), 1u);
  EXPECT_EQ(recent.InNewestFrame().newest_points, 1u);
  // A non-finite pose breaks the chain of odometry: everything is forgotten.
  EXPECT_TRUE(recent.Add(SeenFrom({1, 0, 0}), {1, 0, 0}));
  EXPECT_EQ(recent.Scans(), 2u);
  EXPECT_FALSE(recent.Add(SeenFrom({2, 0, 0}), {2, 0, INFINITY}));
  EXPECT_EQ(recent.Scans(), 0u);
  const auto refused = [](auto change, const char* option) {
    RecentScansOptions options;
    change(options);
    try {
      RecentScans bad(options);
      ADD_FAILURE() << option << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
    }
  };
  refused([](RecentScansOptions& o) { o.max_scans = 0; }, "max_scans");
  refused([](RecentScansOptions& o) { o.max_travel_m = NAN; }, "max_travel_m");
  refused([](RecentScansOptions& o) { o.min_spacing_m = 0.0; }, "min_spacing_m");
  refused([](RecentScansOptions& o) { o.min_turn_rad = 4.0; }, "min_turn_rad");
}

bool Close(const geometry::Pose2D& a, const geometry::Pose2D& b) {
  return std::hypot(a.x - b.x, a.y - b.y) <= 0.2 &&
         std::abs(geometry::WrapAngle(a.theta - b.theta)) <= 5.0 * geometry::kPi / 180.0;
}

// A 10 m x 6 m room with a door in the middle of its south wall to a
// corridor below. From (6, 1.2) looking east a 180 deg laser sees the east
// part of the room only, and the room turned by half a turn (laser at
// (4, 4.8) looking west) fits that scan as well. The robot came along the
// corridor and through the door: those scans tell the two apart.
TEST(RecentScans, ScansOnTheWayThereTellARoomFromItsTwin) {
  using world_model::MakeWall;
  const world_model::WorldModel map(
      "room and corridor",
      {MakeWall(1, {0, 0}, {4.5, 0}), MakeWall(2, {5.5, 0}, {10, 0}), MakeWall(3, {10, 0}, {10, 6}),
       MakeWall(4, {10, 6}, {0, 6}), MakeWall(5, {0, 6}, {0, 0}),
       MakeWall(6, {0, -1.6}, {10, -1.6}), MakeWall(7, {10, -1.6}, {10, 0}),
       MakeWall(8, {0, 0}, {0, -1.6})},
      {}, {});
  const auto scene = world_model::Scene::FromWorld(map);
  const GlobalLocaliser localiser(map, GlobalLocaliserOptions{});
  std::mt19937 rng(4);
  const testing::ScanSpec laser{361, geometry::kPi, 30.0, 0.01};
  const auto points = [&](const geometry::Pose2D& pose) {
    const auto scan = testing::CastScan(scene, pose, laser, rng);
    return ScanPointsInLaserFrame(scan.ranges, scan.angle_min, scan.angle_increment, 0.0,
                                  scan.max_range_m - 1e-3);
  };
  const geometry::Pose2D truth{6.0, 1.2, 0.0};
  const auto alone = localiser.Locate(points(truth));
  EXPECT_NE(alone.decision, GlobalDecision::kFound);  // the twin fits as well

  // East along the corridor, north through the door, east to the truth,
  // a scan every half metre or eighth of a turn; odometry 1.5 % long,
  // drifting 0.3 deg per metre.
  const double quarter = geometry::kPi / 2;
  const std::vector<geometry::Pose2D> path = {{4.0, -0.8, 0.0},
                                              {4.5, -0.8, 0.0},
                                              {5.0, -0.8, 0.0},
                                              {5.0, -0.8, quarter / 2},
                                              {5.0, -0.8, quarter},
                                              {5.0, -0.3, quarter},
                                              {5.0, 0.2, quarter},
                                              {5.0, 0.7, quarter},
                                              {5.0, 1.2, quarter},
                                              {5.0, 1.2, quarter / 2},
                                              {5.0, 1.2, 0.0},
                                              {5.5, 1.2, 0.0},
                                              truth};
  RecentScans recent;
  geometry::Pose2D odometry{0, 0, 0};
  for (size_t i = 0; i < path.size(); ++i) {
    if (i > 0) {
      geometry::Pose2D step = geometry::Between(path[i - 1], path[i]);
      const double metres = std::hypot(step.x, step.y);
      step = {1.015 * step.x, 1.015 * step.y, step.theta + 0.3 * geometry::kPi / 180.0 * metres};
      odometry = geometry::Compose(odometry, step);
    }
    recent.Add(points(path[i]), odometry);
  }
  EXPECT_EQ(recent.Scans(), 10u);  // the options' most
  const auto together = localiser.Locate(recent.InNewestFrame());
  // The newest scan needs readings of its own: with too few, no answer from
  // the earlier scans alone.
  Readings newest_blind = recent.InNewestFrame();
  newest_blind.points.erase(newest_blind.points.begin() + 3,
                            newest_blind.points.begin() + *newest_blind.newest_points);
  newest_blind.seen_from.erase(newest_blind.seen_from.begin() + 3,
                               newest_blind.seen_from.begin() + *newest_blind.newest_points);
  newest_blind.newest_points = 3;
  const auto blind = localiser.Locate(newest_blind);
  EXPECT_EQ(blind.decision, GlobalDecision::kNotFound);
  EXPECT_NE(blind.reason.find("newest scan"), std::string::npos) << blind.reason;
  // Readings that do not fit together are refused.
  Readings broken = recent.InNewestFrame();
  broken.seen_from.pop_back();
  EXPECT_THROW(localiser.Locate(broken), std::invalid_argument);
  broken = recent.InNewestFrame();
  broken.newest_points = broken.points.size() + 1;
  EXPECT_THROW(localiser.Locate(broken), std::invalid_argument);

  ASSERT_EQ(together.decision, GlobalDecision::kFound)
      << together.reason << ": best " << together.best->score << " at " << together.best->pose.x
      << " " << together.best->pose.y << " " << together.best->pose.theta << ", runner-up "
      << together.runner_up->score << " at " << together.runner_up->pose.x << " "
      << together.runner_up->pose.y << " " << together.runner_up->pose.theta;
  EXPECT_TRUE(Close(together.best->pose, truth))
      << together.best->pose.x << " " << together.best->pose.y << " " << together.best->pose.theta;
}

}  // namespace
}  // namespace structloc::localisation_core
