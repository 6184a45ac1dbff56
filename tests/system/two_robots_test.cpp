// Several robots on one DDS domain, kept apart by ROS 2 namespaces: the
// namespace rules (without a participant), and the two-robot launch file run
// for real: each robot's localisation follows its own robot's ground truth,
// 17 m from the other robot, and nothing is published outside the namespaces.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <mutex>
#include <optional>

#include "dds_test_support.hpp"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "structloc/config/strict_xml.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/dds_common/topic_namespace.hpp"
#include "structloc/geometry/pose2d.hpp"
#include "structloc/process/child_process.hpp"
#include "test_domains.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = testing::domains::kTwoRobots;

TEST(TopicNamespace, MovesEveryRosTopicIntoTheNamespace) {
  EXPECT_EQ(dds_common::InNamespace(dds_common::topics::kScan, "robot1").name, "rt/robot1/scan");
  EXPECT_EQ(dds_common::InNamespace(dds_common::topics::kStatus, "fleet/r2").name,
            "rt/fleet/r2/structloc/status");
  EXPECT_EQ(dds_common::InNamespace(dds_common::topics::kTf, "robot1").qos_profile,
            dds_common::topics::kTf.qos_profile);
  EXPECT_EQ(dds_common::InNamespace(dds_common::topics::kScan, "").name, "rt/scan");
  EXPECT_EQ(dds_common::InNamespace({"plain", "sensor_data"}, "robot1").name, "plain");
}

TEST(TopicNamespace, NormalisesSlashesAndRefusesNamesRos2Refuses) {
  EXPECT_EQ(dds_common::NormaliseNamespace("/robot1/"), "robot1");
  EXPECT_EQ(dds_common::NormaliseNamespace("fleet/_r2"), "fleet/_r2");
  EXPECT_EQ(dds_common::NormaliseNamespace("/"), "");
  EXPECT_EQ(dds_common::NormaliseNamespace(""), "");
  for (const char* bad : {"1robot", "robot 1", "fleet//r1", "r-1", "robot1/../x"}) {
    EXPECT_THROW(dds_common::NormaliseNamespace(bad), config::ConfigError) << bad;
  }
}

// Per namespace: the newest estimate with its stamp, and the true poses by stamp.
struct Track {
  std::mutex mutex;
  std::map<std::string, std::pair<double, geometry::Pose2D>> estimate;
  std::map<std::string, std::map<double, geometry::Pose2D>> truth;
  size_t unqualified = 0;  // samples on the topics without a namespace

  // The true pose of `ns` at the stamp of its newest estimate (nullopt if none within 10 ms).
  std::optional<geometry::Pose2D> TruthAtEstimate(const std::string& ns) {
    const auto& by_stamp = truth[ns];
    const double t = estimate[ns].first;
    auto it = by_stamp.lower_bound(t - 0.01);
    if (it == by_stamp.end() || it->first > t + 0.01) return std::nullopt;
    return it->second;
  }
};

TEST(TwoRobots, EachLocalisationFollowsItsOwnRobot) {
  Track track;
  dds_common::Node observer(testing::TestNodeOptions("two_robot_observer", kDomain));
  std::vector<dds_common::Subscription> subscriptions;
  for (const std::string ns : {"robot1", "robot2"}) {
    subscriptions.push_back(
        observer.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
            dds_common::InNamespace(dds_common::topics::kPose, ns),
            [&track, ns](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
              const auto& p = m.pose().pose();
              std::lock_guard<std::mutex> lock(track.mutex);
              track.estimate[ns] = {dds_common::FromRosTime(m.header().stamp()),
                                    {p.position().x(), p.position().y(),
                                     dds_common::YawFromQuaternion(p.orientation())}};
            }));
    subscriptions.push_back(observer.Subscribe<nav_msgs::msg::OdometryPubSubType>(
        dds_common::InNamespace(dds_common::topics::kGroundTruth, ns),
        [&track, ns](const nav_msgs::msg::Odometry& m) {
          const auto& p = m.pose().pose();
          std::lock_guard<std::mutex> lock(track.mutex);
          track.truth[ns][dds_common::FromRosTime(m.header().stamp())] = {
              p.position().x(), p.position().y(), dds_common::YawFromQuaternion(p.orientation())};
        }));
  }
  subscriptions.push_back(
      observer.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
          dds_common::topics::kPose,
          [&track](const geometry_msgs::msg::PoseWithCovarianceStamped&) {
            std::lock_guard<std::mutex> lock(track.mutex);
            ++track.unqualified;
          }));
  process::ChildProcess launch(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc",
      {"launch", testing::SourcePath("launch_xml/two_robots.launch.xml"),
       "domain:=" + std::to_string(kDomain), "qos:=" + testing::ShippedQos(), "--duration", "8"});
  // Sampled while both run: each estimate near its own truth, far from the other robot.
  size_t checks = 0;
  double worst = 0.0;
  const auto until = std::chrono::steady_clock::now() + 7s;
  while (std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(200ms);
    std::lock_guard<std::mutex> lock(track.mutex);
    if (track.estimate.size() < 2 || track.truth.size() < 2) continue;
    for (const std::string ns : {"robot1", "robot2"}) {
      const std::string other = ns == "robot1" ? "robot2" : "robot1";
      const auto own_truth = track.TruthAtEstimate(ns);
      if (!own_truth || track.truth[other].empty()) continue;
      const Eigen::Vector2d at = track.estimate[ns].second.Translation();
      const double own = (at - own_truth->Translation()).norm();
      const double apart = (at - track.truth[other].rbegin()->second.Translation()).norm();
      worst = std::max(worst, own);
      EXPECT_LT(own, 0.03) << ns << " is off its own robot";
      EXPECT_GT(apart, 5.0) << ns << " follows the other robot";
      ++checks;
    }
  }
  const auto code = launch.WaitExit(testing::kGenerousTimeout);
  ASSERT_TRUE(code.has_value()) << launch.CapturedOutput();
  EXPECT_EQ(*code, 0) << launch.CapturedOutput();
  std::printf("two robots: %zu checks, worst estimate %.1f mm from its own robot\n", checks,
              1000 * worst);
  EXPECT_GE(checks, 10u) << launch.CapturedOutput();
  std::lock_guard<std::mutex> lock(track.mutex);
  EXPECT_EQ(track.unqualified, 0u) << "a pose was published outside the namespaces";
  EXPECT_NE(launch.CapturedOutput().find("rt/robot1/scan"), std::string::npos)
      << launch.CapturedOutput();
}

}  // namespace
}  // namespace structloc
