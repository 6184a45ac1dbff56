// Global localisation in the component (issue 12): started with no initial
// pose and no saved state, the localisation component locates the robot from
// the scans against the whole map and then tracks it as if it had been given
// the pose; asked on rt/reinitialize_global_localization, it drops its pose
// and locates the robot again; an approximate pose on rt/initialpose is
// confirmed by a local search around it, also one sent before any odometry.
// Real processes on a real Fast DDS domain.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "dds_test_support.hpp"
#include "geometry_msgs/msg/PoseArrayPubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "live_accuracy.hpp"
#include "std_msgs/msg/EmptyPubSubTypes.h"
#include "structloc/dds_common/component_runtime.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/evaluation/live_evaluator.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"
#include "test_domains.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = testing::domains::kLocalisationGlobalStart;

// The office run with a localisation started without a pose, watched by an
// observer that judges it against the simulator's ground truth. The robot
// (the simulator) starts with it unless the test starts it later.
struct RunWithoutPose {
  enum class Robot { kStarted, kLater };
  // `scenario_file` under maps/scenarios; `extra`: more localisation arguments.
  explicit RunWithoutPose(const std::string& observer_name, Robot robot = Robot::kStarted,
                          const std::string& scenario_file = "office_people.xml",
                          std::vector<std::string> extra = {})
      : scenario_path(testing::SourcePath("maps/scenarios/" + scenario_file)),
        scenario(simulation_core::LoadScenario(scenario_path)),
        observer(testing::TestNodeOptions(observer_name, kDomain)),
        evaluator(observer, scenario.initial_pose),
        localisation(std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
                     Arguments(std::move(extra))) {
    if (robot == Robot::kStarted) StartRobot();
  }
  static std::vector<std::string> Arguments(std::vector<std::string> extra) {
    std::vector<std::string> args = {"--domain", std::to_string(kDomain),
                                     "--qos",    testing::ShippedQos(),
                                     "--params", testing::SimulatedRobotParams()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
  void StartRobot() {
    simulator.emplace(
        std::string(STRUCTLOC_BIN_DIR) + "/structloc_simulator",
        std::vector<std::string>{"--domain", std::to_string(kDomain), "--qos",
                                 testing::ShippedQos(), "--scenario", scenario_path, "--time-scale",
                                 "2", "--wait-for-subscribers", "1", "--exit-when-done"});
  }
  // The accuracy bar from 1 s after `start` on.
  void ExpectAccurateAfter(double start, const std::string& what) {
    testing::ExpectDemoAccuracy(
        testing::ErrorFromOneSecondAfter(evaluator.Estimate(), evaluator.Truth(), start), what);
  }
  void Stop() {
    if (simulator) simulator->Signal(SIGTERM);
    localisation.Signal(SIGTERM);
    EXPECT_EQ(localisation.WaitExit(testing::kGenerousTimeout), 0);
  }

  const std::string scenario_path;
  const simulation_core::Scenario scenario;
  dds_common::Node observer;
  evaluation::LiveEvaluator evaluator;
  process::ChildProcess localisation;
  std::optional<process::ChildProcess> simulator;
};

// An operator's pose, 0.8 m and 3 deg off the truth `truth`, as RViz's "2D Pose
// Estimate" sends it (its covariance).
geometry_msgs::msg::PoseWithCovarianceStamped ApproximatePose(const geometry::Pose2D& truth,
                                                              double stamp) {
  geometry_msgs::msg::PoseWithCovarianceStamped given;
  given.header().stamp(dds_common::ToRosTime(stamp));
  given.header().frame_id("map");
  given.pose().pose().position().x(truth.x + 0.7);
  given.pose().pose().position().y(truth.y - 0.4);
  given.pose().pose().orientation(dds_common::ToQuaternion(truth.theta + 0.05));
  given.pose().covariance()[0] = given.pose().covariance()[7] = 0.25;
  given.pose().covariance()[35] = 0.068;
  return given;
}

TEST(LocalisationGlobalStart, LocatesTheRobotWithoutAPoseAndAgainWhenAsked) {
  RunWithoutPose run("global_start_observer");
  auto& evaluator = run.evaluator;
  auto& localisation = run.localisation;
  auto request = run.observer.CreateWriter<std_msgs::msg::EmptyPubSubType>(
      dds_common::topics::kReinitializeGlobalLocalization);
  // What it says while it weighs hypotheses (issue 38).
  std::mutex seen_mutex;
  size_t most_poses = 0, holding_statuses = 0;
  bool weights_fit = true;
  auto hypotheses = run.observer.Subscribe<geometry_msgs::msg::PoseArrayPubSubType>(
      dds_common::topics::kHypotheses, [&](const geometry_msgs::msg::PoseArray& m) {
        std::lock_guard<std::mutex> lock(seen_mutex);
        if (m.header().frame_id() == "map") most_poses = std::max(most_poses, m.poses().size());
      });
  auto statuses = run.observer.Subscribe<structloc_msgs::msg::LocalisationStatusPubSubType>(
      dds_common::topics::kStatus, [&](const structloc_msgs::msg::LocalisationStatus& m) {
        if (m.phase() != "holding") return;
        std::lock_guard<std::mutex> lock(seen_mutex);
        ++holding_statuses;
        double sum = 0.0;
        for (double w : m.hypothesis_weights()) sum += w;
        weights_fit = weights_fit && m.hypothesis_weights().size() >= 2 && std::abs(sum - 1) < 1e-9;
      });
  ASSERT_TRUE(testing::WaitUntil([&] { return evaluator.Estimate().size() > 40; }, 60s))
      << localisation.CapturedOutput();
  const std::string started = localisation.CapturedOutput();
  EXPECT_NE(started.find("no initial pose: locating the robot globally"), std::string::npos)
      << started;
  EXPECT_NE(started.find("global localisation at t="), std::string::npos) << started;
  // The robot drives from the start along a corridor that repeats: an
  // ambiguous first search starts hypotheses that its driving tells apart
  // (issue 38), or a later attempt searches with the scans before it,
  // placed by odometry.
  EXPECT_TRUE(started.find("committed to one of") != std::string::npos ||
              started.find("scans before it") != std::string::npos)
      << started;
  EXPECT_NE(started.find("initial pose set from global localisation"), std::string::npos)
      << started;
  if (started.find("committed to one of") != std::string::npos) {
    std::lock_guard<std::mutex> lock(seen_mutex);
    std::printf("hypotheses committed: at most %zu on %s, %zu statuses holding\n", most_poses,
                dds_common::topics::kHypotheses.name.c_str(), holding_statuses);
    EXPECT_GE(most_poses, 2u);
    EXPECT_GT(holding_statuses, 0u);
    EXPECT_TRUE(weights_fit);
  }
  // Tracking from the first pose found on, after a second to settle.
  run.ExpectAccurateAfter(evaluator.Estimate().front().stamp, "located globally");

  // Carried away (as far as the component knows): asked to relocalise.
  ASSERT_TRUE(testing::WaitUntil([&] { return request.MatchedReaders() > 0; }, 30s));
  const double asked = evaluator.Estimate().back().stamp;
  const size_t before = evaluator.Estimate().size();
  ASSERT_TRUE(request.Write(std_msgs::msg::Empty{}));
  ASSERT_TRUE(testing::WaitUntil(
      [&] {
        const auto out = localisation.CapturedOutput();
        return out.find("relocalising globally") != std::string::npos &&
               evaluator.Estimate().size() > before + 30;
      },
      60s))
      << localisation.CapturedOutput();
  run.ExpectAccurateAfter(asked + 0.5, "relocalising, taken as 0.5 s after the request");
  run.Stop();
}

// An operator's pose (RViz's "2D Pose Estimate", with its covariance) is
// approximate: published 0.8 m and 3 deg off while the robot drives, it is
// confirmed by a local search around it, not tracked from where it was put.
TEST(LocalisationGlobalStart, AnOperatorsApproximatePoseIsConfirmedNearby) {
  RunWithoutPose run("operator_pose_observer");
  auto& evaluator = run.evaluator;
  auto operator_pose =
      run.observer.CreateWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
          dds_common::topics::kInitialPose);
  ASSERT_TRUE(testing::WaitUntil([&] { return evaluator.Estimate().size() > 40; }, 60s))
      << run.localisation.CapturedOutput();
  ASSERT_TRUE(testing::WaitUntil([&] { return operator_pose.MatchedReaders() > 0; }, 30s));
  const auto truth = evaluator.Truth().back();
  const size_t before = evaluator.Estimate().size();
  ASSERT_TRUE(operator_pose.Write(ApproximatePose(truth.pose, truth.stamp)));
  ASSERT_TRUE(testing::WaitUntil([&] { return evaluator.Estimate().size() > before + 40; }, 60s))
      << run.localisation.CapturedOutput();
  EXPECT_NE(run.localisation.CapturedOutput().find("the pose on rt/initialpose confirmed"),
            std::string::npos)
      << run.localisation.CapturedOutput();
  run.ExpectAccurateAfter(truth.stamp, "a pose given 0.81 m and 3 deg off");
  run.Stop();
}

// The same pose sent before the robot's odometry is up: the localisation
// holds it for the first odometry sample, then confirms it in the same way.
TEST(LocalisationGlobalStart, AnOperatorsPoseBeforeAnyOdometryIsConfirmedToo) {
  RunWithoutPose run("early_operator_observer", RunWithoutPose::Robot::kLater);
  auto operator_pose =
      run.observer.CreateWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
          dds_common::topics::kInitialPose);
  ASSERT_TRUE(testing::WaitUntil([&] { return operator_pose.MatchedReaders() > 0; }, 30s));
  ASSERT_TRUE(operator_pose.Write(
      ApproximatePose(run.scenario.initial_pose, dds_common::WallClockSeconds())));
  ASSERT_TRUE(testing::WaitUntil(
      [&] {
        return run.localisation.CapturedOutput().find(
                   "initial pose held for the first odometry from rt/initialpose") !=
               std::string::npos;
      },
      30s))
      << run.localisation.CapturedOutput();
  run.StartRobot();
  ASSERT_TRUE(testing::WaitUntil([&] { return run.evaluator.Estimate().size() > 80; }, 60s))
      << run.localisation.CapturedOutput();
  EXPECT_NE(run.localisation.CapturedOutput().find("the pose on rt/initialpose confirmed"),
            std::string::npos)
      << run.localisation.CapturedOutput();
  run.ExpectAccurateAfter(run.evaluator.Estimate().front().stamp,
                          "a pose given 0.81 m and 3 deg off before any odometry");
  run.Stop();
}

// A robot carried away while tracked (maps/scenarios/office_kidnap.xml: at
// 20 s lifted from the corridor's east part and put down 17 m west, its
// odometry seeing nothing; issue 38): the component finds out by itself that
// the scans no longer fit, searches the whole map, moves the tracking to
// where the robot is and reports the kidnapping; from then on it tracks as
// well as ever.
TEST(LocalisationGlobalStart, AKidnappedRobotIsFoundAgainWithoutARequest) {
  RunWithoutPose run("kidnap_observer", RunWithoutPose::Robot::kStarted, "office_kidnap.xml",
                     {"--initial-pose", "2.0 6.5 0"});
  auto& localisation = run.localisation;
  const std::string marker = "localisation: kidnapped: at t=";
  ASSERT_TRUE(testing::WaitUntil(
      [&] { return localisation.CapturedOutput().find(marker) != std::string::npos; }, 90s))
      << localisation.CapturedOutput();
  const std::string resumed = "after the old track's last pose at t=";
  ASSERT_TRUE(testing::WaitUntil(
      [&] { return localisation.CapturedOutput().find(resumed) != std::string::npos; }, 10s))
      << localisation.CapturedOutput();
  const std::string out = localisation.CapturedOutput();
  const double found_at = std::stod(out.substr(out.find(marker) + marker.size()));
  // Poses of scans taken while the search ran are of the old track (how many
  // depends on how fast the machine searched); the bar holds from 1 s after.
  const double old_track_until = std::stod(out.substr(out.find(resumed) + resumed.size()));
  ASSERT_TRUE(testing::WaitUntil(
      [&] { return run.evaluator.Estimate().back().stamp > old_track_until + 8.0; }, 60s));
  run.ExpectAccurateAfter(old_track_until, "found again after the kidnapping");
  // The first pose after the teleport (20 s after the first scan) is where
  // the robot was put down, not where it was lifted.
  const auto truth = run.evaluator.Truth();
  ASSERT_FALSE(truth.empty());
  EXPECT_GT(found_at, truth.front().stamp + 20.0);
  EXPECT_LT(found_at, truth.front().stamp + 20.0 + 10.0) << "found again within 10 s";
  std::printf("kidnapped at %.1f s, found again at %.1f s\n", 20.0, found_at - truth.front().stamp);
  run.Stop();
}

}  // namespace
}  // namespace structloc
