// A feeder for tests of the running localisation component over real DDS: it
// plays the simulated office on rt/scan and rt/odom from its own participant
// (the robot standing for a second first, as the component's start pose
// applies to the first odometry), lets a test replace or add samples, and
// collects the published poses and the component's diagnostics.
#pragma once

#include <functional>
#include <map>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "dds_test_support.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/simulator/sim_conversions.hpp"

namespace structloc::testing {

class LocalisationFeed {
 public:
  static constexpr double kClockOffset = 1.0e9;  // simulation time -> message stamps

  LocalisationFeed(const std::string& name, int domain)
      : node_(TestNodeOptions(name, domain)),
        scans_(
            node_.CreateWriter<sensor_msgs::msg::LaserScanPubSubType>(dds_common::topics::kScan)),
        odometry_(node_.CreateWriter<nav_msgs::msg::OdometryPubSubType>(dds_common::topics::kOdom)),
        initial_pose_(node_.CreateWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
            dds_common::topics::kInitialPose)) {
    pose_subscription_ = node_.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
        dds_common::topics::kPose, [this](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
          const auto& p = m.pose().pose();
          const geometry::Pose2D pose{p.position().x(), p.position().y(),
                                      dds_common::YawFromQuaternion(p.orientation())};
          bool finite = geometry::IsFinite(pose);
          for (double c : m.pose().covariance()) finite = finite && std::isfinite(c);
          std::lock_guard<std::mutex> lock(mutex_);
          non_finite_pose_ = non_finite_pose_ || !finite;
          poses_.emplace_back(dds_common::FromRosTime(m.header().stamp()), pose);
        });
    diagnostics_subscription_ = node_.Subscribe<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
        dds_common::topics::kDiagnostics, [this](const diagnostic_msgs::msg::DiagnosticArray& a) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& s : a.status()) {
            if (s.name() != "structloc/localisation") continue;
            level_ = s.level();
            message_ = s.message();
            messages_.push_back(s.message());
            for (const auto& kv : s.values()) values_[kv.key()] = kv.value();
          }
        });
  }

  bool WaitForLocalisation(std::chrono::seconds timeout) {
    return WaitUntil([&] { return scans_.MatchedReaders() > 0 && odometry_.MatchedReaders() > 0; },
                     timeout);
  }

  // Called for every scan (index k from 1) before it is sent; it may change
  // the scan or send other samples itself. Return false to not send the scan.
  using Hook = std::function<bool(int k, const simulation_core::SimState& state,
                                  sensor_msgs::msg::LaserScan& scan)>;

  // Plays the scenario; returns the true pose of every scan sent, by stamp.
  void Play(const simulation_core::Scenario& scenario, const Hook& hook) {
    simulation_core::Simulation sim(scenario);
    for (int k = 100; k > 0; --k) {
      auto standing = simulator::ToOdometry(sim.State(), 0.0, kClockOffset - 0.01 * k);
      odometry_.Write(standing);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));  // paces the publisher
    }
    long steps = 0;
    int k = 0;
    while (!sim.Finished()) {
      const auto& s = sim.Step();
      if (++steps % 2 == 0) {
        auto odom = simulator::ToOdometry(s, 0.0, kClockOffset);
        odometry_.Write(odom);
      }
      auto scan = sim.TakeScan();
      if (!scan) continue;
      // 50 Hz, faster than the lasers of the presets: a component that keeps
      // up with its scanner is not made to drop scans by a test's own load.
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      auto message = simulator::ToLaserScan(*scan, kClockOffset);
      if (hook && !hook(++k, s, message)) continue;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        truth_.emplace(kClockOffset + scan->stamp, scan->truth);
      }
      scans_.Write(message);
    }
  }

  // Largest position error of the published poses against the truth of their scans.
  double WorstError() {
    std::lock_guard<std::mutex> lock(mutex_);
    double worst = 0.0;
    for (const auto& [stamp, pose] : poses_) {
      auto it = truth_.lower_bound(stamp - 1e-6);
      if (it == truth_.end() || std::abs(it->first - stamp) > 1e-6) continue;
      worst = std::max(worst, (pose.Translation() - it->second.Translation()).norm());
    }
    return worst;
  }

  size_t Poses() {
    std::lock_guard<std::mutex> lock(mutex_);
    return poses_.size();
  }
  // Scans the component dropped for overload (the newest scan wins), as its
  // diagnostics last said: a loaded test machine may make it drop some.
  size_t ScansDropped() {
    const auto dropped = Value("scans_dropped");
    return dropped.empty() ? 0u : std::stoul(dropped);
  }
  // Scans answered: with a pose, or dropped for a newer one. The last poses
  // may still be on their way and the dropped count comes with the
  // diagnostics, about once a second: a test waits for what it expects.
  size_t Answered() { return Poses() + ScansDropped(); }
  bool NonFinitePoseSeen() {
    std::lock_guard<std::mutex> lock(mutex_);
    return non_finite_pose_;
  }
  std::string Value(const std::string& key) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = values_.find(key);
    return it == values_.end() ? "" : it->second;
  }
  std::pair<int, std::string> Headline() {
    std::lock_guard<std::mutex> lock(mutex_);
    return {level_, message_};
  }
  bool AnyMessageContains(const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& m : messages_) {
      if (m.find(text) != std::string::npos) return true;
    }
    return false;
  }

  dds_common::TopicWriter<sensor_msgs::msg::LaserScanPubSubType>& ScanWriter() { return scans_; }
  dds_common::TopicWriter<nav_msgs::msg::OdometryPubSubType>& OdometryWriter() { return odometry_; }
  dds_common::TopicWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>&
  InitialPoseWriter() {
    return initial_pose_;
  }
  dds_common::Node& Node() { return node_; }

 private:
  dds_common::Node node_;
  dds_common::TopicWriter<sensor_msgs::msg::LaserScanPubSubType> scans_;
  dds_common::TopicWriter<nav_msgs::msg::OdometryPubSubType> odometry_;
  dds_common::TopicWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType> initial_pose_;
  std::mutex mutex_;
  std::vector<std::pair<double, geometry::Pose2D>> poses_;
  std::map<double, geometry::Pose2D> truth_;
  bool non_finite_pose_ = false;
  int level_ = -1;
  std::string message_;
  std::vector<std::string> messages_;
  std::map<std::string, std::string> values_;
  // Last: destroyed first, before what their callbacks write.
  dds_common::Subscription pose_subscription_;
  dds_common::Subscription diagnostics_subscription_;
};

}  // namespace structloc::testing
