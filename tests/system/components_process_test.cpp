// The three component executables as real processes on a loopback DDS domain:
// they start, report their endpoints, exchange samples, stop cleanly on
// SIGINT/SIGTERM, and exit non-zero on bad configuration. Waits are on
// conditions (a diagnostic value, an exit); their timeouts only guard hangs.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "dds_test_support.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "structloc/dds_common/component_runtime.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"
#include "wait_until.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
using process::ChildProcess;

std::string BinPath(const std::string& name) {
  return std::string(STRUCTLOC_BIN_DIR) + "/" + name;
}

constexpr int kDomain = testing::domains::kComponentsProcess;

std::vector<std::string> Args(int domain, const std::string& qos = testing::ShippedQos()) {
  return {"--domain", std::to_string(domain), "--qos", qos};
}

// Latest diagnostic key/values per component name.
class DiagnosticsListener {
 public:
  explicit DiagnosticsListener(dds_common::Node& node) {
    subscription_ = node.Subscribe<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
        dds_common::topics::kDiagnostics, [this](const diagnostic_msgs::msg::DiagnosticArray& a) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& s : a.status()) {
            headlines_[s.name()] = s.message();
            for (const auto& kv : s.values()) latest_[s.name()][kv.key()] = kv.value();
          }
        });
  }
  long Value(const std::string& component, const std::string& key) {
    const std::string text = Text(component, key);
    return text.empty() ? -1 : std::stol(text);
  }
  std::string Text(const std::string& component, const std::string& key) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto c = latest_.find(component);
    if (c == latest_.end()) return "";
    auto k = c->second.find(key);
    return k == c->second.end() ? "" : k->second;
  }
  std::string Headline(const std::string& component) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto h = headlines_.find(component);
    return h == headlines_.end() ? "" : h->second;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::map<std::string, std::string>> latest_;
  std::map<std::string, std::string> headlines_;
  dds_common::Subscription subscription_;  // last: destroyed first
};

TEST(Components, ExchangeSamplesAndStopCleanly) {
  dds_common::Node observer(testing::TestNodeOptions("observer", kDomain));
  DiagnosticsListener diagnostics(observer);
  ChildProcess simulator(BinPath("structloc_simulator"), Args(kDomain));
  ChildProcess localisation(BinPath("structloc_localisation"), Args(kDomain));
  ChildProcess calibration(BinPath("structloc_calibration"), Args(kDomain));

  EXPECT_TRUE(testing::WaitUntil([&] {
    return diagnostics.Value("structloc/localisation", "scans_rejected") > 0 ||
           diagnostics.Value("structloc/localisation", "scans_processed") > 0;
  })) << localisation.CapturedOutput();
  EXPECT_TRUE(testing::WaitUntil([&] {
    return diagnostics.Value("structloc/calibration", "encoder_samples") > 0;
  })) << calibration.CapturedOutput();

  simulator.Signal(SIGINT);
  localisation.Signal(SIGTERM);
  calibration.Signal(SIGTERM);
  EXPECT_EQ(simulator.WaitExit(testing::kGenerousTimeout), 0) << simulator.CapturedOutput();
  EXPECT_EQ(localisation.WaitExit(testing::kGenerousTimeout), 0) << localisation.CapturedOutput();
  EXPECT_EQ(calibration.WaitExit(testing::kGenerousTimeout), 0) << calibration.CapturedOutput();
  const auto report = localisation.CapturedOutput();
  EXPECT_NE(report.find("subscribes rt/scan  [sensor_msgs::msg::dds_::LaserScan_]"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("publishes  rt/pose"), std::string::npos) << report;
  EXPECT_NE(report.find("stopped cleanly"), std::string::npos) << report;
  // Started without --params, it took the preset the simulated laser's
  // geometry names (1081 beams at 0.25 deg: a Hokuyo UTM-30LX) and the
  // laser's mounting that the simulator publishes on rt/tf_static.
  EXPECT_NE(report.find("parameters: maps/params/hokuyo_utm30lx.xml, chosen from the first scan"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("laser mounting x 0.200 m, y 0.000 m, yaw 0.00 deg from rt/tf_static "
                        "(base_link -> laser)"),
            std::string::npos)
      << report;
}

// Without --params and with no scan yet it waits for one, says so on
// rt/diagnostics, and a stop signal ends the wait cleanly.
TEST(Components, WithoutParamsItWaitsForTheFirstScanAndStopsCleanly) {
  dds_common::Node observer(testing::TestNodeOptions("waiting_observer", kDomain));
  DiagnosticsListener diagnostics(observer);
  ChildProcess localisation(BinPath("structloc_localisation"), Args(kDomain));
  ASSERT_TRUE(testing::WaitUntil([&] {
    return localisation.CapturedOutput().find("waiting for the first scan") != std::string::npos;
  })) << localisation.CapturedOutput();
  ASSERT_TRUE(testing::WaitUntil([&] {
    return diagnostics.Text("structloc/localisation", "start_up") == "waiting for the first scan";
  })) << localisation.CapturedOutput();
  EXPECT_NE(diagnostics.Headline("structloc/localisation").find("no scans on rt/scan yet for "),
            std::string::npos)
      << diagnostics.Headline("structloc/localisation");
  localisation.Signal(SIGTERM);
  EXPECT_EQ(localisation.WaitExit(testing::kGenerousTimeout), 0) << localisation.CapturedOutput();
  EXPECT_NE(localisation.CapturedOutput().find("stopped cleanly before it started"),
            std::string::npos)
      << localisation.CapturedOutput();
}

// A pose an operator sends while it waits for the first scan (the laser not
// yet running) is not lost: the component, made once the scan came, takes it
// like one sent later.
TEST(Components, WithoutParamsAPoseSentWhileItWaitsForTheFirstScanIsKept) {
  dds_common::Node observer(testing::TestNodeOptions("waiting_pose_observer", kDomain));
  auto operator_pose =
      observer.CreateWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
          dds_common::topics::kInitialPose);
  ChildProcess localisation(BinPath("structloc_localisation"), Args(kDomain));
  ASSERT_TRUE(testing::WaitUntil([&] {
    return localisation.CapturedOutput().find("waiting for the first scan") != std::string::npos;
  })) << localisation.CapturedOutput();
  ASSERT_TRUE(testing::WaitUntil([&] { return operator_pose.MatchedReaders() > 0; }));
  const auto scenario = simulation_core::LoadScenario(
      testing::SourcePath("maps/scenarios/office_people.xml"));  // the simulator's default
  geometry_msgs::msg::PoseWithCovarianceStamped given;
  given.header().stamp(dds_common::ToRosTime(dds_common::WallClockSeconds()));
  given.header().frame_id("map");
  given.pose().pose().position().x(scenario.initial_pose.x);
  given.pose().pose().position().y(scenario.initial_pose.y);
  given.pose().pose().orientation(dds_common::ToQuaternion(scenario.initial_pose.theta));
  given.pose().covariance()[0] = given.pose().covariance()[7] = 0.01;
  given.pose().covariance()[35] = 0.01;
  ASSERT_TRUE(operator_pose.Write(given));
  ChildProcess simulator(BinPath("structloc_simulator"), Args(kDomain));
  ASSERT_TRUE(testing::WaitUntil([&] {
    return localisation.CapturedOutput().find("from rt/initialpose") != std::string::npos;
  })) << localisation.CapturedOutput();
  const auto report = localisation.CapturedOutput();
  EXPECT_NE(report.find("a pose came on rt/initialpose while waiting for the first scan"),
            std::string::npos)
      << report;
  // Held for the first odometry, or set at once when odometry came first (the
  // simulator starts publishing as the component is made): kept either way.
  EXPECT_TRUE(report.find("initial pose held for the first odometry from rt/initialpose") !=
                  std::string::npos ||
              report.find("initial pose set from rt/initialpose") != std::string::npos)
      << report;
  simulator.Signal(SIGINT);
  localisation.Signal(SIGTERM);
  EXPECT_EQ(simulator.WaitExit(testing::kGenerousTimeout), 0) << simulator.CapturedOutput();
  EXPECT_EQ(localisation.WaitExit(testing::kGenerousTimeout), 0) << report;
}

// A robot whose description places the laser through a frame between (as
// URDFs do: base_link -> laser_mount -> laser) publishes both transforms on
// rt/tf_static; the mounting is their composition, not the last one alone.
TEST(Components, WithoutParamsTheMountingComposesTheTransformsDownToTheLaser) {
  dds_common::Node robot(testing::TestNodeOptions("mounted_robot", kDomain));
  auto statics =
      robot.CreateWriter<tf2_msgs::msg::TFMessagePubSubType>(dds_common::topics::kTfStatic);
  auto scans = robot.CreateWriter<sensor_msgs::msg::LaserScanPubSubType>(dds_common::topics::kScan);
  ChildProcess localisation(BinPath("structloc_localisation"), Args(kDomain));
  auto transform = [](const std::string& parent, const std::string& child, double x, double yaw) {
    geometry_msgs::msg::TransformStamped t;
    t.header().frame_id(parent);
    t.child_frame_id(child);
    t.transform().translation().x(x);
    t.transform().rotation(dds_common::ToQuaternion(yaw));
    return t;
  };
  tf2_msgs::msg::TFMessage mounting;
  mounting.transforms().push_back(transform("base_link", "laser_mount", 0.1, geometry::kHalfPi));
  mounting.transforms().push_back(transform("laser_mount", "laser", 0.2, 0.0));
  ASSERT_TRUE(testing::WaitUntil([&] { return statics.MatchedReaders() > 0; }))
      << localisation.CapturedOutput();
  ASSERT_TRUE(statics.Write(mounting));
  sensor_msgs::msg::LaserScan scan;  // a Hokuyo UTM-30LX's geometry
  scan.header().frame_id("laser");
  scan.angle_min(-2.356194f);
  scan.angle_increment(0.004363323f);
  scan.angle_max(2.356194f);
  scan.range_min(0.1f);
  scan.range_max(30.0f);
  scan.ranges().assign(1081, 3.0f);
  ASSERT_TRUE(testing::WaitUntil([&] {
    scans.Write(scan);
    return localisation.CapturedOutput().find("laser mounting") != std::string::npos;
  })) << localisation.CapturedOutput();
  const auto report = localisation.CapturedOutput();
  EXPECT_NE(report.find("laser mounting x 0.100 m, y 0.200 m, yaw 90.00 deg from rt/tf_static "
                        "(base_link -> laser_mount -> laser)"),
            std::string::npos)
      << report;
  localisation.Signal(SIGTERM);
  EXPECT_EQ(localisation.WaitExit(testing::kGenerousTimeout), 0) << report;
}

// How fast it fails is printed, not asserted (a loaded machine is slower).
TEST(Components, BrokenProfileExitsNonZeroNamingFileAndProblem) {
  const testing::TempDir dir;
  std::string text = testing::ReadFile(testing::ShippedQos());
  text.replace(text.find("<depth>5</depth>"), 16, "<depth>0</depth>");
  const std::string path = dir.Write("broken_qos.xml", text);
  for (const auto* exe :
       {"structloc_simulator", "structloc_localisation", "structloc_calibration"}) {
    const auto start = std::chrono::steady_clock::now();
    ChildProcess child(BinPath(exe), Args(testing::domains::kComponentsBrokenProfile, path));
    const auto code = child.WaitExit(testing::kGenerousTimeout);
    const auto elapsed = std::chrono::steady_clock::now() - start;
    ASSERT_TRUE(code.has_value()) << exe << " did not exit";
    EXPECT_NE(*code, 0) << exe;
    std::printf("%s refused the broken profile after %.0f ms\n", exe,
                std::chrono::duration<double, std::milli>(elapsed).count());
    const auto out = child.CapturedOutput();
    EXPECT_NE(out.find(path), std::string::npos) << out;
    EXPECT_NE(out.find("history depth '0'"), std::string::npos) << out;
  }
}

TEST(Components, MissingQosFileAndUnknownOptionAreConfigurationErrors) {
  ChildProcess missing(BinPath("structloc_localisation"),
                       Args(testing::domains::kComponentsBrokenProfile, "/nonexistent.xml"));
  EXPECT_EQ(missing.WaitExit(testing::kGenerousTimeout), 2);
  EXPECT_NE(missing.CapturedOutput().find("/nonexistent.xml: cannot open file"), std::string::npos)
      << missing.CapturedOutput();
  ChildProcess unknown(BinPath("structloc_simulator"), {"--no-such-option", "1"});
  EXPECT_EQ(unknown.WaitExit(testing::kGenerousTimeout), 2);
  EXPECT_NE(unknown.CapturedOutput().find("unknown option '--no-such-option'"), std::string::npos);
}

}  // namespace
}  // namespace structloc
