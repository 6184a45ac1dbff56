// The DDS ownership contract: a subscription is a handle owned by its
// subscriber, so an object destroyed while samples are still arriving is never
// called back once its destruction has begun, and a callback running at that
// moment is waited for; callbacks held while a component is built are
// released without deadlock while samples keep arriving. Real participants,
// samples flooding in throughout.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <memory>
#include <thread>
#include <vector>

#include "dds_test_support.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/localisation/localisation_component.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"
#include "test_domains.hpp"

namespace structloc {
namespace {

constexpr int kDomain = testing::domains::kComponentTeardown;

// Publishes odometry (and, when asked, scans) as fast as it can until destroyed.
class Flood {
 public:
  explicit Flood(bool scans)
      : node_(testing::TestNodeOptions("flood", kDomain)),
        odom_(node_.CreateWriter<nav_msgs::msg::OdometryPubSubType>(dds_common::topics::kOdom)),
        scan_(
            node_.CreateWriter<sensor_msgs::msg::LaserScanPubSubType>(dds_common::topics::kScan)) {
    thread_ = std::thread([this, scans] {
      double t = 1000.0;
      while (!stop_) {
        t += 0.01;
        nav_msgs::msg::Odometry odom;
        odom.header().stamp(dds_common::ToRosTime(t));
        odom.pose().pose().orientation(dds_common::ToQuaternion(0.0));
        odom_.Write(odom);
        if (scans) {
          sensor_msgs::msg::LaserScan scan;
          scan.header().stamp(dds_common::ToRosTime(t - 0.005));
          scan.angle_min(-2.35f);
          scan.angle_increment(static_cast<float>(4.7 / 1080));
          scan.angle_max(2.35f);
          scan.range_max(30.0f);
          scan.ranges(std::vector<float>(1081, 4.0f));
          scan_.Write(scan);
        }
        std::this_thread::sleep_for(std::chrono::microseconds(500));
      }
    });
  }
  ~Flood() {
    stop_ = true;
    thread_.join();
  }
  // Readers matched on both topics (the scan count only when scans flood).
  size_t MatchedOdometryReaders() const { return odom_.MatchedReaders(); }
  size_t MatchedScanReaders() const { return scan_.MatchedReaders(); }

 private:
  dds_common::Node node_;
  dds_common::TopicWriter<nav_msgs::msg::OdometryPubSubType> odom_;
  dds_common::TopicWriter<sensor_msgs::msg::LaserScanPubSubType> scan_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// What the test sees of a subscriber from outside it.
struct Observed {
  std::atomic<int> calls{0};
  std::atomic<bool> in_callback{false};
  std::atomic<bool> destroyed{false};
  std::atomic<int> calls_after_destruction{0};
};

// A subscriber whose callback is slow and writes into the subscriber's own
// members, the way a component's does.
class SlowSubscriber {
 public:
  SlowSubscriber(dds_common::Node& node, Observed& observed)
      : observed_(observed), received_(std::make_unique<std::vector<double>>()) {
    subscription_ = node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
        dds_common::topics::kOdom, [this](const nav_msgs::msg::Odometry& m) {
          observed_.in_callback = true;
          if (observed_.destroyed) ++observed_.calls_after_destruction;
          received_->push_back(dds_common::FromRosTime(m.header().stamp()));
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
          ++observed_.calls;
          observed_.in_callback = false;
        });
  }

 private:
  Observed& observed_;
  std::unique_ptr<std::vector<double>> received_;
  dds_common::Subscription subscription_;  // last: destroyed first
};

TEST(ComponentTeardown, NoCallbackReachesASubscriberOnceItIsDestroyed) {
  dds_common::Node node(testing::TestNodeOptions("subscriber", kDomain));
  Flood flood(false);
  for (int round = 0; round < 5; ++round) {
    Observed observed;
    auto subscriber = std::make_unique<SlowSubscriber>(node, observed);
    ASSERT_TRUE(testing::WaitUntil([&] { return observed.calls > 5; }, std::chrono::seconds(20)))
        << "round " << round << ": no odometry arrived";
    subscriber.reset();  // while samples keep arriving
    EXPECT_FALSE(observed.in_callback) << "a callback was still running in a destroyed object";
    observed.destroyed = true;
    const int calls = observed.calls;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    EXPECT_EQ(observed.calls_after_destruction, 0) << "round " << round;
    EXPECT_EQ(observed.calls, calls) << "round " << round;
  }
}

TEST(ComponentTeardown, ALocalisationComponentDestroyedWhileScansArriveDoesNotCrash) {
  dds_common::Node node(testing::TestNodeOptions("localisation", kDomain));
  Flood flood(true);
  // Statuses are published once per tracked scan: proof that scans were being
  // processed when the component went away.
  std::atomic<int> statuses{0};
  const auto status_subscription =
      node.Subscribe<structloc_msgs::msg::LocalisationStatusPubSubType>(
          dds_common::topics::kStatus,
          [&statuses](const structloc_msgs::msg::LocalisationStatus&) { ++statuses; });
  const std::string params = testing::SourcePath("maps/params/office_sick.xml");
  for (int round = 0; round < 3; ++round) {
    localisation::LocalisationComponentOptions options;
    options.initial_pose = geometry::Pose2D{19.5, 6.5, 0.2};
    auto component = std::make_unique<localisation::LocalisationComponent>(
        node,
        std::make_unique<world_model::WorldModel>(
            world_model::LoadWorldModel(testing::SourcePath("maps/office_floor.xml"))),
        localisation_core::LoadLocaliserOptions(params),
        localisation_core::LoadSessionOptions(params), options);
    ASSERT_TRUE(testing::WaitUntil(
        [&] { return flood.MatchedOdometryReaders() > 0 && flood.MatchedScanReaders() > 0; },
        std::chrono::seconds(20)))
        << "round " << round << ": the component's readers never matched";
    const int before = statuses;
    ASSERT_TRUE(testing::WaitUntil(
        [&] {
          component->Step();
          return statuses > before + 5;
        },
        std::chrono::seconds(30)))
        << "round " << round << ": no scan was processed";
    component.reset();  // mid-stream, without Stop() first
  }
}

// A component is built with callbacks held (Node::HoldCallbacks); releasing
// them takes what waited, on the releasing thread, while DDS threads deliver
// new samples. Fast DDS calls a listener with the reader's lock held and
// taking a sample takes that lock, so neither side may wait for the other:
// once it did, and a restarted component hung at start-up now and then. The
// slow callback widens the window in which a new sample arrives mid-release.
TEST(ComponentTeardown, ReleasingHeldCallbacksWhileSamplesArriveNeverDeadlocks) {
  Flood flood(false);
  for (int round = 0; round < 10; ++round) {
    dds_common::Node node(testing::TestNodeOptions("held", kDomain));
    node.HoldCallbacks();
    std::atomic<int> calls{0};
    const auto subscription = node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
        dds_common::topics::kOdom, [&calls](const nav_msgs::msg::Odometry&) {
          std::this_thread::sleep_for(std::chrono::microseconds(300));
          ++calls;
        });
    ASSERT_TRUE(testing::WaitUntil([&] { return subscription.MatchedWriters() > 0; },
                                   std::chrono::seconds(20)))
        << "round " << round << ": the reader never matched";
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // samples wait meanwhile
    auto released = std::async(std::launch::async, [&node] { node.ReleaseCallbacks(); });
    if (released.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
      // The releasing thread is stuck for good: nothing can be cleaned up.
      std::fprintf(stderr, "round %d: ReleaseCallbacks deadlocked with a DDS thread\n", round);
      std::_Exit(1);
    }
    const int after_release = calls;
    EXPECT_TRUE(
        testing::WaitUntil([&] { return calls > after_release + 5; }, std::chrono::seconds(20)))
        << "round " << round << ": callbacks did not flow after the release";
  }
}

}  // namespace
}  // namespace structloc
