// Bad input through real DataWriters: the localisation component receives a
// good simulated stream interleaved with every kind of bad scan and odometry
// sample (REP-117 specials, NaN, inf, zero or mismatched beam counts, an
// angle_increment of 0, stamps out of order or far in the future, odometry
// jumps and NaNs). It must stay up, report what it rejected and why, never
// publish a NaN, and keep localising on the good data.
#include <gtest/gtest.h>

#include <map>
#include <mutex>

#include "child_process.hpp"
#include "dds_test_support.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "ros_conversions.hpp"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "sim_conversions.hpp"
#include "test_domains.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = testing::domains::kLocalisationBadInput;

TEST(LocalisationBadInput, StaysUpReportsRejectionsAndKeepsLocalising) {
  auto scenario = simulation::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  scenario.duration_s = 8.0;
  dds::Node feeder(testing::TestNodeOptions("bad_input_feeder", kDomain));
  auto scan_writer = feeder.CreateWriter<sensor_msgs::msg::LaserScanPubSubType>(dds::topics::kScan);
  auto odom_writer = feeder.CreateWriter<nav_msgs::msg::OdometryPubSubType>(dds::topics::kOdom);
  std::mutex mutex;
  std::vector<std::pair<double, geometry::Pose2D>> poses;
  bool nan_seen = false;
  std::map<std::string, std::string> diagnostics;
  feeder.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      dds::topics::kPose, [&](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
        std::lock_guard<std::mutex> lock(mutex);
        const auto& p = m.pose().pose();
        const geometry::Pose2D pose{p.position().x(), p.position().y(),
                                    dds::YawFromQuaternion(p.orientation())};
        bool finite = geometry::IsFinite(pose);
        for (double c : m.pose().covariance()) finite = finite && std::isfinite(c);
        nan_seen = nan_seen || !finite;
        poses.emplace_back(dds::FromRosTime(m.header().stamp()), pose);
      });
  feeder.Subscribe<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
      dds::topics::kDiagnostics, [&](const diagnostic_msgs::msg::DiagnosticArray& a) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& s : a.status()) {
          if (s.name() != "structloc/localisation") continue;
          for (const auto& kv : s.values()) diagnostics[kv.key()] = kv.value();
        }
      });
  const auto& p0 = scenario.initial_pose;
  process::ChildProcess localisation(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--initial-pose",
       std::to_string(p0.x) + " " + std::to_string(p0.y) + " " + std::to_string(p0.theta)});
  ASSERT_TRUE(testing::WaitUntil(
      [&] { return scan_writer.MatchedReaders() > 0 && odom_writer.MatchedReaders() > 0; }, 10s));

  simulation::Simulation sim(scenario);
  const double offset = 1.0e9;
  // The robot stands still for a second while the localisation comes up
  // (its start pose applies to the first odometry it receives).
  for (int k = 100; k > 0; --k) {
    auto standing = simulator::ToOdometry(sim.State(), 0.0, offset - 0.01 * k);
    odom_writer.Write(standing);
    std::this_thread::sleep_for(10ms);
  }
  std::vector<std::pair<double, geometry::Pose2D>> truth;
  int bad_sent = 0;
  double distance = 0.0;
  long steps = 0;
  while (!sim.Finished()) {
    const auto& s = sim.Step();
    ++steps;
    if (steps % 2 == 0) {
      auto odom = simulator::ToOdometry(s, distance, offset);
      odom_writer.Write(odom);
    }
    auto scan = sim.TakeScan();
    if (!scan) continue;
    truth.emplace_back(offset + scan->stamp, scan->truth);
    // Pace the stream a little: the test is about robustness, not load.
    std::this_thread::sleep_for(5ms);
    const auto good = simulator::ToLaserScan(*scan, offset);
    const int k = static_cast<int>(truth.size());
    if (k % 3 == 0) {
      // One bad input of each kind, in turn, between good scans.
      auto bad = good;
      switch ((k / 3) % 9) {
        case 0:
          for (auto& r : bad.ranges()) r = std::nanf("");
          break;  // processed: every beam counted as non-finite, robot reported lost
        case 1:
          bad.ranges().clear();
          break;
        case 2:
          bad.ranges().resize(bad.ranges().size() / 2);
          break;
        case 3:
          bad.angle_increment(0.0f);
          break;
        case 4:
          bad.header().stamp(dds::ToRosTime(offset + scan->stamp - 5.0));
          break;
        case 5:
          bad.header().stamp(dds::ToRosTime(offset + scan->stamp + 3600.0));
          break;
        case 6:
          for (size_t i = 0; i < bad.ranges().size(); i += 2) {
            bad.ranges()[i] = std::numeric_limits<float>::infinity();  // REP-117: no return
          }
          break;
        case 7: {
          auto jump = simulator::ToOdometry(s, distance, offset);
          jump.header().stamp(dds::ToRosTime(offset + s.time + 0.001));
          jump.pose().pose().position().x(1e6);
          odom_writer.Write(jump);
          break;
        }
        case 8: {
          auto nan = simulator::ToOdometry(s, distance, offset);
          nan.header().stamp(dds::ToRosTime(offset + s.time + 0.002));
          nan.pose().pose().position().y(std::nan(""));
          odom_writer.Write(nan);
          break;
        }
      }
      if ((k / 3) % 9 <= 6) scan_writer.Write(bad);
      ++bad_sent;
      std::this_thread::sleep_for(5ms);
    }
    auto g = good;
    if (k % 3 != 0) scan_writer.Write(g);
  }
  std::this_thread::sleep_for(1500ms);
  EXPECT_FALSE(localisation.Poll().has_value()) << "the component died:\n"
                                                << localisation.CapturedOutput();
  std::lock_guard<std::mutex> lock(mutex);
  EXPECT_FALSE(nan_seen);
  EXPECT_GT(bad_sent, 20);
  // Rejections are reported with their reasons.
  for (const auto* reason :
       {"rejected: empty scan", "rejected: beam count does not match the scan angles",
        "rejected: angle_increment zero or non-finite, or bad limits",
        "rejected: scan stamp not after the previous scan",
        "rejected: scan stamp too far ahead of the odometry",
        "rejected: odometry jump faster than max_odometry_speed_m_s or "
        "max_odometry_turn_rate_rad_s",
        "rejected: odometry pose or stamp not finite, or its orientation not a unit quaternion"}) {
    EXPECT_TRUE(diagnostics.count(reason) && std::stol(diagnostics[reason]) > 0) << reason;
  }
  // And it kept localising on the good scans.
  ASSERT_GT(poses.size(), truth.size() / 2);
  double worst = 0.0;
  for (const auto& [stamp, pose] : poses) {
    for (const auto& [ts, t] : truth) {
      if (std::abs(ts - stamp) > 1e-6) continue;
      const double e = (pose.Translation() - t.Translation()).norm();
      if (e > 0.03) std::printf("t = %.3f s: error %.3f m\n", ts - offset, e);
      worst = std::max(worst, e);
    }
  }
  EXPECT_LT(worst, 0.03);
}

}  // namespace
}  // namespace structloc
