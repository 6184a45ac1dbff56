// HypothesisTracker (issue 38) on the point-symmetric office floor
// (maps/symmetric_office.xml): seeded with the robot's pose and its twin
// turned by 180 deg about the floor's centre, it drops the twin and commits
// to the truth once the one asymmetric detail comes into view; a robot
// standing still never decides, however many scans it takes; hypotheses
// that explain nothing are given up for a fresh search; bad options are
// named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

#include "structloc/localisation_core/global/hypothesis_tracker.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "synthetic_scans.hpp"
#include "test_paths.hpp"

namespace structloc::localisation_core {
namespace {

const geometry::Pose2D kMount{0.2, 0.0, 0.0};

// The floor turned by 180 deg about its centre (15, 7).
geometry::Pose2D Twin(const geometry::Pose2D& p) {
  return {30.0 - p.x, 14.0 - p.y, geometry::WrapAngle(p.theta + geometry::kPi)};
}

struct SymmetricFloor {
  SymmetricFloor()
      : world(world_model::LoadWorldModel(testing::SourcePath("maps/symmetric_office.xml"))),
        scene(world_model::Scene::FromWorld(world)),
        localiser(world, GlobalLocaliserOptions{}) {}
  // Laser-frame points of a 270 deg, 1081-beam scan from the robot at `robot`.
  std::vector<Eigen::Vector2d> Scan(const geometry::Pose2D& robot) {
    testing::ScanSpec spec;
    spec.beams = 1081;
    spec.field_of_view_rad = 1.5 * geometry::kPi;
    spec.noise_sigma_m = 0.01;
    const auto s = testing::CastScan(scene, geometry::Compose(robot, kMount), spec, rng);
    return ScanPointsInLaserFrame(s.ranges, s.angle_min, s.angle_increment, 0.05, 29.9);
  }
  // A search's answer that cannot tell `robot` from the poses given.
  static GlobalResult Tie(const std::vector<geometry::Pose2D>& robots) {
    GlobalResult result;
    result.decision = GlobalDecision::kAmbiguous;
    for (const auto& r : robots)
      result.candidates.push_back({geometry::Compose(r, kMount), 0.9, std::nullopt});
    return result;
  }

  world_model::WorldModel world;
  world_model::Scene scene;
  GlobalLocaliser localiser;
  std::mt19937 rng{5};
};

TEST(HypothesisTracker, DropsTheTwinAndCommitsOnceTheDetailIsInView) {
  SymmetricFloor floor;
  HypothesisTracker tracker(floor.localiser, kMount);
  geometry::Pose2D robot{12.0, 7.0, 0.0};  // west of the recess at x = 23..24.5, driving east
  ASSERT_EQ(tracker.Seed(SymmetricFloor::Tie({robot, Twin(robot)}), floor.Scan(robot), robot), 2u);
  std::optional<geometry::Pose2D> committed_at;
  while (robot.x < 26.0 && !committed_at) {
    robot.x += 0.08;  // 0.8 m/s at 10 Hz; perfect odometry (the map frame's)
    const auto verdict = tracker.Update(floor.Scan(robot), robot);
    ASSERT_NE(verdict, HypothesisTracker::Verdict::kSearch);
    if (verdict == HypothesisTracker::Verdict::kCommitted) committed_at = robot;
  }
  ASSERT_TRUE(committed_at.has_value());
  const auto& h = *tracker.Committed();
  EXPECT_LT(std::hypot(h.pose.x - robot.x, h.pose.y - robot.y), 0.05);
  EXPECT_LT(std::abs(geometry::WrapAngle(h.pose.theta - robot.theta)), 0.02);
  EXPECT_GT(tracker.StepsCounted(), 0u);
  EXPECT_NEAR(tracker.TravelM(), committed_at->x - 12.0, 1e-9);
  std::printf("committed at x = %.2f m after %.2f m and %zu steps\n", committed_at->x,
              tracker.TravelM(), tracker.StepsCounted());
}

TEST(HypothesisTracker, ARobotStandingStillNeverDecides) {
  SymmetricFloor floor;
  HypothesisTracker tracker(floor.localiser, kMount);
  const geometry::Pose2D robot{8.0, 7.0, 0.0};
  tracker.Seed(SymmetricFloor::Tie({robot, Twin(robot)}), floor.Scan(robot), robot);
  for (int i = 0; i < 300; ++i) {
    EXPECT_EQ(tracker.Update(floor.Scan(robot), robot), HypothesisTracker::Verdict::kHolding);
  }
  EXPECT_EQ(tracker.StepsCounted(), 0u);
  EXPECT_EQ(tracker.Hypotheses().size(), 2u);
}

TEST(HypothesisTracker, HypothesesThatExplainNothingAreGivenUp) {
  SymmetricFloor floor;
  HypothesisTracker tracker(floor.localiser, kMount);
  geometry::Pose2D robot{8.0, 7.0, 0.0};
  // Both seeds inside rooms, facing walls: neither explains the corridor's scans.
  tracker.Seed(SymmetricFloor::Tie({{2.0, 11.0, 1.0}, {27.0, 3.0, -2.0}}), floor.Scan(robot),
               robot);
  HypothesisTracker::Verdict verdict = HypothesisTracker::Verdict::kHolding;
  for (int i = 0; i < 100 && verdict == HypothesisTracker::Verdict::kHolding; ++i) {
    robot.x += 0.08;
    verdict = tracker.Update(floor.Scan(robot), robot);
  }
  EXPECT_EQ(verdict, HypothesisTracker::Verdict::kSearch);
  EXPECT_FALSE(tracker.Holding());
  EXPECT_FALSE(tracker.Committed().has_value());
}

TEST(HypothesisTracker, OptionsOutOfRangeAreNamed) {
  SymmetricFloor floor;
  auto refused = [&](auto change, const std::string& name) {
    HypothesisOptions o;
    change(o);
    try {
      HypothesisTracker tracker(floor.localiser, kMount, o);
      ADD_FAILURE() << name << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  refused([](HypothesisOptions& o) { o.readings_per_step = 0.0; }, "readings_per_step");
  refused([](HypothesisOptions& o) { o.max_hypotheses = 0; }, "max_hypotheses");
  refused([](HypothesisOptions& o) { o.unexplained_likelihood = 1.0; }, "unexplained_likelihood");
  refused([](HypothesisOptions& o) { o.evidence_step_m = -1.0; }, "evidence_step_m");
  refused([](HypothesisOptions& o) { o.decision_log_ratio = NAN; }, "decision_log_ratio");
}

}  // namespace
}  // namespace structloc::localisation_core
