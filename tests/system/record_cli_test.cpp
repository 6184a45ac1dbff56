// `structloc record` end to end over DDS: the simulator drives the office
// tour, record writes its laser and odometry to a CARMEN log (the mounting
// from rt/tf_static), its wheel encoders and ground truth beside it, and
// replay localises the recorded log as accurately as the demo's bar asks.
// Then the map from the raw recording: `structloc slam` corrects the tour's
// poses and builds a map on them that explains the scans, and replay
// localises the log on that map, never lost and within the bar for a map
// built from a recording (50 mm RMSE after one rigid alignment). How
// accurate the path and that localisation are is judged on the same tour
// simulated offline (self_built_map_test.cpp): a loaded machine drops a few
// scans from a live recording, and which ones moves the self-built map by
// centimetres (the maps guide gives the spread).
// Stopped by Ctrl-C mid-run, record writes everything it received: a log
// that reads without a malformed line.
#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <string>

#include "cli_runner.hpp"
#include "dds_test_support.hpp"
#include "live_accuracy.hpp"
#include "self_built_map.hpp"
#include "structloc/log_formats/carmen_reader.hpp"
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
  const auto built = testing::MapAndLocalise(o, truth, temp.Path());
  ASSERT_EQ(built.slam.exit_code, 0) << built.slam.output;
  testing::ExpectMapExplainsItsScans(built);
  EXPECT_EQ(built.path.size(), scans);
  EXPECT_EQ(built.on_own_map.scans_used, scans);
  EXPECT_EQ(built.on_own_map.scans_lost, 0u);
  EXPECT_LE(built.on_own_map_error.position_rmse_m, 0.05);
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
