// `structloc record` end to end over DDS: the simulator drives the office
// tour, record writes its laser and odometry to a CARMEN log (the mounting
// from rt/tf_static), its wheel encoders and ground truth beside it, and
// replay localises the recorded log as accurately as the demo's bar asks.
// Then the map from the raw recording: `structloc slam` corrects the tour's
// poses and builds a map on them, and replay localises the log on that map.
// A self-built map has a frame of its own, so both are judged after one
// rigid alignment to the truth: the SLAM path by the real recordings' bars
// with odometry errors (RMSE <= 50 mm, max <= 200 mm), the localisation on
// the self-built map by the demo's (10 mm, 30 mm).
// Stopped by Ctrl-C mid-run, record writes everything it received: a log
// that reads without a malformed line.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "cli_runner.hpp"
#include "dds_test_support.hpp"
#include "live_accuracy.hpp"
#include "structloc/log_formats/carmen_reader.hpp"
#include "structloc/log_formats/tum_reader.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/replay/replay.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"
#include "wait_until.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = testing::domains::kRecordCli;

process::ChildProcess StartRecord(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"record", "--domain", std::to_string(kDomain), "--qos",
                                   testing::ShippedQos()};
  args.insert(args.end(), extra.begin(), extra.end());
  return process::ChildProcess(std::string(STRUCTLOC_BIN_DIR) + "/structloc", args);
}

process::ChildProcess StartSimulator() {
  return process::ChildProcess(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_simulator",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--scenario",
       testing::SourcePath("maps/scenarios/office_people.xml"), "--time-scale", "4",
       "--wait-for-subscribers", "1", "--exit-when-done"});
}

// RMSE and max of `estimate` against `truth` (stamps within 11 ms) after the
// rigid motion that fits them best (2-D Umeyama without scale).
std::pair<double, double> AlignedError(const std::vector<log_formats::StampedPose>& estimate,
                                       const std::vector<log_formats::StampedPose>& truth) {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> pairs;
  for (const auto& e : estimate) {
    if (const auto* t = log_formats::Nearest(truth, e.stamp, 0.011))
      pairs.push_back({e.pose.Translation(), t->pose.Translation()});
  }
  if (pairs.empty()) return {1e9, 1e9};
  Eigen::Vector2d me = Eigen::Vector2d::Zero(), mt = Eigen::Vector2d::Zero();
  for (const auto& [e, t] : pairs) {
    me += e;
    mt += t;
  }
  me /= static_cast<double>(pairs.size());
  mt /= static_cast<double>(pairs.size());
  double sc = 0.0, ss = 0.0;
  for (const auto& [e, t] : pairs) {
    const Eigen::Vector2d a = e - me, b = t - mt;
    sc += a.dot(b);
    ss += a.x() * b.y() - a.y() * b.x();
  }
  const double theta = std::atan2(ss, sc);
  const Eigen::Rotation2Dd r(theta);
  double sum = 0.0, worst = 0.0;
  for (const auto& [e, t] : pairs) {
    const double d = (r * (e - me) + mt - t).norm();
    sum += d * d;
    worst = std::max(worst, d);
  }
  return {std::sqrt(sum / static_cast<double>(pairs.size())), worst};
}

size_t Lines(const std::string& path) {
  std::ifstream in(path);
  size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

TEST(RecordCli, ARecordedTourReplaysAndMapsItself) {
  const testing::TempDir temp;
  const std::string log = temp / "run.log", truth = temp / "truth.tum";
  const std::string encoders = temp / "encoders.csv";
  auto record = StartRecord(
      {"--out", log, "--truth-out", truth, "--encoders-out", encoders, "--quiet-s", "3"});
  auto simulator = StartSimulator();
  ASSERT_EQ(simulator.WaitExit(180s), 0) << simulator.CapturedOutput();
  ASSERT_EQ(record.WaitExit(testing::kGenerousTimeout), 0) << record.CapturedOutput();
  const std::string said = record.CapturedOutput();
  EXPECT_NE(
      said.find(
          "the laser's mounting from rt/tf_static (base_link -> laser): (0.200, 0.000, 0.000)"),
      std::string::npos)
      << said;

  // Every laser line of the tour (the simulator publishes one a scan period,
  // 597 over the office tour, as `structloc simulate` records offline), with
  // no malformed line.
  log_formats::CarmenReader reader(log, {});
  log_formats::CarmenRecord r;
  size_t scans = 0, odometry = 0;
  while (reader.Next(r))
    (r.kind == log_formats::CarmenRecord::Kind::kOdometry ? odometry : scans)++;
  EXPECT_EQ(reader.Stats().malformed, 0u);
  EXPECT_GE(scans, 590u);
  EXPECT_LE(scans, 597u);
  EXPECT_GT(odometry, 5 * scans - 100);
  EXPECT_GT(Lines(encoders), 2000u);
  EXPECT_GT(Lines(truth), 2000u);

  const auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  replay::ReplayOptions o;
  o.map_path = testing::SourcePath("maps/office_floor.xml");
  o.log_path = log;
  o.initial_pose = scenario.initial_pose;
  o.params_path = testing::SimulatedRobotParams();
  o.truth_path = truth;
  o.out_tum = temp / "estimate.tum";
  const auto report = replay::RunReplay(o);
  EXPECT_NEAR(report.sensor_mount.x, 0.2, 1e-9);
  EXPECT_EQ(report.scans_used, scans);
  ASSERT_TRUE(report.estimate_error);
  testing::ExpectDemoAccuracy(*report.estimate_error, "the recorded tour replayed");

  // The map from the raw recording, and localisation on it.
  const std::string world = temp / "slam_world.xml", slam_path = temp / "slam.tum";
  const std::string picture = temp / "slam.png";
  const auto slam = testing::RunCli(
      {"slam", "--log", log, "--poses-out", slam_path, "--out", world, "--plot", picture}, 300s);
  ASSERT_EQ(slam.exit_code, 0) << slam.output;
  // The built map checked against the scans it was built from: every wall
  // seen by them, and most of their readings on a wall (people and the
  // recording's noise aside).
  std::smatch explained, walls;
  ASSERT_TRUE(std::regex_search(slam.output, explained,
                                std::regex("of a wall or pillar: ([0-9.]+) % explained")))
      << slam.output;
  EXPECT_GE(std::stod(explained[1]), 80.0) << slam.output;
  ASSERT_TRUE(std::regex_search(slam.output, walls, std::regex(", ([0-9]+) never seen")))
      << slam.output;
  EXPECT_EQ(walls[1], "0") << slam.output;
  EXPECT_TRUE(std::filesystem::exists(picture));
  const auto truth_poses = log_formats::ReadTum(truth);
  const auto path = log_formats::ReadTum(slam_path);
  ASSERT_EQ(path.size(), scans);
  const auto [slam_rmse, slam_max] = AlignedError(path, truth_poses);
  std::printf("slam path, aligned: RMSE %.1f mm, max %.1f mm\n", 1e3 * slam_rmse, 1e3 * slam_max);
  EXPECT_LE(slam_rmse, 0.05);
  EXPECT_LE(slam_max, 0.2);
  replay::ReplayOptions on_own = o;
  on_own.map_path = world;
  on_own.initial_pose = path.front().pose;
  on_own.truth_path.clear();
  on_own.out_tum = temp / "on_own_map.tum";
  const auto own = replay::RunReplay(on_own);
  EXPECT_EQ(own.scans_used, scans);
  EXPECT_EQ(own.scans_lost, 0u);
  const auto [own_rmse, own_max] = AlignedError(own.estimate, truth_poses);
  std::printf("localised on the self-built map, aligned: RMSE %.1f mm, max %.1f mm\n",
              1e3 * own_rmse, 1e3 * own_max);
  EXPECT_LE(own_rmse, 0.01);
  EXPECT_LE(own_max, 0.03);
}

TEST(RecordCli, CtrlCMidRunWritesEverythingReceived) {
  const testing::TempDir temp;
  const std::string log = temp / "run.log";
  auto record = StartRecord({"--out", log});
  auto simulator = StartSimulator();
  ASSERT_TRUE(testing::WaitUntil(
      [&] { return record.CapturedOutput().find("mounting") != std::string::npos; }, 30s))
      << record.CapturedOutput();
  std::this_thread::sleep_for(3s);
  record.Signal(SIGINT);
  ASSERT_EQ(record.WaitExit(testing::kGenerousTimeout), 0) << record.CapturedOutput();
  simulator.Signal(SIGTERM);
  simulator.WaitExit(testing::kGenerousTimeout);
  const std::string said = record.CapturedOutput();
  const size_t at = said.find("stopped (Ctrl-C or SIGTERM): ");
  ASSERT_NE(at, std::string::npos) << said;
  const size_t said_scans = std::stoul(said.substr(at + 29));
  log_formats::CarmenReader reader(log, {});
  log_formats::CarmenRecord r;
  size_t scans = 0;
  while (reader.Next(r)) scans += r.kind == log_formats::CarmenRecord::Kind::kOdometry ? 0 : 1;
  EXPECT_EQ(reader.Stats().malformed, 0u);
  EXPECT_GT(scans, 20u);
  EXPECT_EQ(scans, said_scans) << said;
}

}  // namespace
}  // namespace structloc
