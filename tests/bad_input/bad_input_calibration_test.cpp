// Regression tests for the bad-input review of 12de806 (calibration defects): each
// test is named after the defect it keeps fixed (H = high, M = medium, L = low).
// The recordings are simulated here with the tricycle model (figure-of-eight
// curves both ways, known parameter errors) so that every test runs in seconds.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <thread>

#include "cli_runner.hpp"
#include "dds_test_support.hpp"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/kinematics/robot_parameters.hpp"
#include "structloc/kinematics/tricycle.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc_msgs/msg/WheelEncodersPubSubTypes.h"
#include "temp_dir.hpp"
#include "test_domains.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using Attributes = std::map<std::string, std::string>;

// A robot file with the shipped tricycle's values, some replaced.
std::string RobotXml(const Attributes& replaced = {}) {
  Attributes a = {{"wheel_radius", "0.185"},       {"axle_distance", "0.62"},
                  {"steering_offset", "0"},        {"traction_ticks_per_rev", "4096"},
                  {"traction_counter_bits", "32"}, {"steering_rad_per_tick", "0.000767"},
                  {"steering_zero_tick", "0"}};
  for (const auto& [key, value] : replaced) a[key] = value;
  std::string xml = "<?xml version=\"1.0\"?>\n<robot";
  for (const auto& [key, value] : a) xml += "\n  " + key + "=\"" + value + "\"";
  return xml + "/>\n";
}

struct Drive {
  uint64_t start_tick = 4294960000u;  // wraps the 32-bit counter early on
  int counter_bits = 32;
  bool constant_traction = false;  // an encoder that never changes
};

struct Recording {
  std::string encoders_csv;
  std::string fixes_csv;
  kinematics::RobotParameters truth;
};

// 100 s of curves both ways at 0.7 m/s with the true robot (radius +1 %,
// axle -2 %, steering offset 0.5 deg): encoders at 100 Hz, noisy fixes at 10 Hz.
Recording Simulate(const Drive& drive) {
  Recording r;
  r.truth.wheel_radius *= 1.01;
  r.truth.axle_distance *= 0.98;
  r.truth.steering_offset = 0.008727;
  const uint64_t mask =
      drive.counter_bits == 64 ? ~uint64_t{0} : (uint64_t{1} << drive.counter_bits) - 1;
  const double ticks_per_rad = r.truth.traction_ticks_per_rev / (2 * geometry::kPi);
  std::mt19937 random(7);
  std::normal_distribution<double> xy_noise(0.0, 0.003), theta_noise(0.0, 0.001);
  std::ostringstream enc, fix;
  enc << "t,traction_ticks,steering_ticks\n" << std::setprecision(12);
  fix << "t,x,y,theta\n" << std::setprecision(12);
  geometry::Pose2D pose;
  double wheel_ticks = 0.0;
  int64_t counted = 0;
  const double dt = 0.01;
  for (int k = 0; k <= 10000; ++k) {
    const double t = 1000.0 + k * dt;
    const double command =
        0.45 * std::sin(2 * geometry::kPi * t / 40) + 0.15 * std::sin(2 * geometry::kPi * t / 11);
    const long steering_ticks =
        std::lround((command - r.truth.steering_offset) / r.truth.steering_rad_per_tick);
    if (k > 0) {
      wheel_ticks += 0.7 * dt / r.truth.wheel_radius * ticks_per_rad;
      const int64_t delta = static_cast<int64_t>(std::floor(wheel_ticks)) - counted;
      counted += delta;
      pose = kinematics::Advance(pose, static_cast<double>(delta) / ticks_per_rad,
                                 r.truth.SteeringAngle(static_cast<double>(steering_ticks)),
                                 r.truth.wheel_radius, r.truth.axle_distance);
    }
    const uint64_t counter = drive.constant_traction
                                 ? 12345u
                                 : (drive.start_tick + static_cast<uint64_t>(counted)) & mask;
    enc << t << "," << counter << "," << steering_ticks << "\n";
    if (k % 10 == 5) {
      fix << t << "," << pose.x + xy_noise(random) << "," << pose.y + xy_noise(random) << ","
          << geometry::WrapAngle(pose.theta + theta_noise(random)) << "\n";
    }
  }
  r.encoders_csv = enc.str();
  r.fixes_csv = fix.str();
  return r;
}

struct CalibrateRun {
  testing::CliResult cli;
  std::string out;  // the --out path
};

CalibrateRun RunCalibrate(const testing::TempDir& dir, const Recording& recording,
                          const std::string& robot_xml, std::vector<std::string> extra = {}) {
  const std::string encoders = dir.Write("encoders.csv", recording.encoders_csv);
  const std::string fixes = dir.Write("fixes.csv", recording.fixes_csv);
  const std::string robot = dir.Write("robot.xml", robot_xml);
  CalibrateRun run;
  run.out = dir / "calibrated.xml";
  std::vector<std::string> args = {"calibrate", "--encoders", encoders, "--fixes", fixes,
                                   "--robot",   robot,        "--out",  run.out};
  args.insert(args.end(), extra.begin(), extra.end());
  run.cli = testing::RunCli(args);
  return run;
}

bool Exists(const std::string& path) {
  return std::ifstream(path).good();
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(BadInputCalibration, M2_ASoundRecordingStillCalibrates) {
  const testing::TempDir dir;
  const auto recording = Simulate({});
  const auto run = RunCalibrate(dir, recording, RobotXml());
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  const auto calibrated = kinematics::LoadRobotParameters(run.out);
  EXPECT_NEAR(calibrated.wheel_radius, recording.truth.wheel_radius,
              0.001 * recording.truth.wheel_radius);
  EXPECT_NEAR(calibrated.axle_distance, recording.truth.axle_distance,
              0.005 * recording.truth.axle_distance);
}

TEST(BadInputCalibration, M2_ConstantEncodersFailWithoutWritingARobotFile) {
  const testing::TempDir dir;
  Drive drive;
  drive.constant_traction = true;
  const auto run = RunCalibrate(dir, Simulate(drive), RobotXml());
  EXPECT_EQ(run.cli.exit_code, 1) << run.cli.output;
  EXPECT_TRUE(Contains(run.cli.output, "calibration FAILED")) << run.cli.output;
  EXPECT_TRUE(Contains(run.cli.output, "traction encoder never changes (always 12345)"))
      << run.cli.output;
  EXPECT_FALSE(Exists(run.out));
}

TEST(BadInputCalibration, M2_ReportSuccessMeansSomethingWasEstimated) {
  const auto recording = Simulate({});
  const testing::TempDir dir;
  auto constant = Simulate({0, 32, true});
  const auto encoders =
      calibration_core::ReadEncodersCsv(dir.Write("encoders.csv", constant.encoders_csv), 32);
  const auto fixes = calibration_core::ReadFixesCsv(dir.Write("fixes.csv", recording.fixes_csv));
  const auto report = calibration_core::Calibrate(encoders, fixes.fixes, {}, {});
  EXPECT_FALSE(report.success);
  EXPECT_FALSE(report.failure.empty());
  ASSERT_FALSE(report.likely_causes.empty());
  EXPECT_TRUE(Contains(report.likely_causes.front(), "never changes"));
}

// Reads a simulated recording back through the CSV readers.
struct Inputs {
  std::vector<calibration_core::EncoderSample> encoders;
  std::vector<calibration_core::Fix> fixes;
};

Inputs Read(const testing::TempDir& dir, const Recording& recording) {
  return {calibration_core::ReadEncodersCsv(dir.Write("encoders.csv", recording.encoders_csv), 32),
          calibration_core::ReadFixesCsv(dir.Write("fixes.csv", recording.fixes_csv)).fixes};
}

TEST(BadInputCalibration, M2_MostlyOutlierIntervalsFail) {
  const testing::TempDir dir;
  auto inputs = Read(dir, Simulate({}));
  // Fixes claiming 0.2 mm accuracy while their noise is 3 mm: intervals are ~15 sigma off.
  const double sigma = 0.0002;
  for (auto& fix : inputs.fixes) {
    fix.has_variance = true;
    fix.variance = {sigma * sigma, sigma * sigma, sigma * sigma};
  }
  const auto report = calibration_core::Calibrate(inputs.encoders, inputs.fixes, {}, {});
  EXPECT_FALSE(report.success);
  EXPECT_TRUE(Contains(report.failure, "fix intervals are outliers")) << report.failure;
}

TEST(BadInputCalibration, M2_DeadReckoningMustImproveOnNominal) {
  const testing::TempDir dir;
  const auto inputs = Read(dir, Simulate({}));
  calibration_core::CalibrationOptions options;
  const auto first = calibration_core::Calibrate(inputs.encoders, inputs.fixes, {}, options);
  EXPECT_TRUE(first.success);
  // Re-calibrating the calibrated robot confirms it (no better, no worse).
  const auto again =
      calibration_core::Calibrate(inputs.encoders, inputs.fixes, first.parameters, options);
  EXPECT_TRUE(again.success) << again.failure;
  options.max_dead_reckoning_ratio = 0.001;  // demands a 1000-fold improvement
  const auto report = calibration_core::Calibrate(inputs.encoders, inputs.fixes, {}, options);
  EXPECT_FALSE(report.success);
  EXPECT_TRUE(Contains(report.failure, "dead reckoning with the estimate is worse"))
      << report.failure;
}

TEST(BadInputCalibration, M2_CounterBitsWiderThanTheDataFailNamingTheWrap) {
  const testing::TempDir dir;
  const auto run = RunCalibrate(dir, Simulate({}), RobotXml({{"traction_counter_bits", "63"}}));
  EXPECT_EQ(run.cli.exit_code, 1) << run.cli.output;
  EXPECT_TRUE(Contains(run.cli.output, "the traction ticks jump by")) << run.cli.output;
  EXPECT_TRUE(Contains(run.cli.output, "seems to wrap at 2^32")) << run.cli.output;
  EXPECT_FALSE(Exists(run.out));
}

TEST(BadInputCalibration, M2_ImplausibleRobotParametersAreRefusedWithFileAndLine) {
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"traction_ticks_per_rev", "1e-300"},
                                                        {"traction_ticks_per_rev", "0.5"},
                                                        {"sensor_x", "1e300"},
                                                        {"wheel_radius", "185"}}) {
    const testing::TempDir dir;
    const auto run = RunCalibrate(dir, Simulate({}), RobotXml({{key, value}}));
    EXPECT_EQ(run.cli.exit_code, 2) << key << "=" << value << "\n" << run.cli.output;
    EXPECT_TRUE(Contains(run.cli.output, dir / "robot.xml:2:")) << run.cli.output;
    EXPECT_TRUE(Contains(run.cli.output, key + " = ")) << run.cli.output;
    EXPECT_FALSE(Exists(run.out));
  }
}

TEST(BadInputCalibration, M3_TractionTicksParsedAsIntegers) {
  // A continuous 63-bit counter near 2^62: a double would round it to 1024 ticks.
  const testing::TempDir dir;
  Drive drive;
  drive.start_tick = uint64_t{1} << 62;
  drive.counter_bits = 63;
  const auto recording = Simulate(drive);
  const auto run = RunCalibrate(dir, recording, RobotXml({{"traction_counter_bits", "63"}}));
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  const auto calibrated = kinematics::LoadRobotParameters(run.out);
  EXPECT_NEAR(calibrated.wheel_radius, recording.truth.wheel_radius,
              0.001 * recording.truth.wheel_radius);
}

TEST(BadInputCalibration, M3_TractionTicksBeyondTheCounterAreRefusedWithFileAndLine) {
  const std::string header = "t,traction_ticks,steering_ticks\n1,0,0\n";
  for (const auto& [ticks, problem] : std::vector<std::pair<std::string, std::string>>{
           {"1e30", "is not a non-negative integer"},
           {"12.5", "is not a non-negative integer"},
           {"-3", "is not a non-negative integer"},
           {"18446744073709551615", "does not fit a 32-bit counter"},
           {"99999999999999999999999", "does not fit a 32-bit counter"},
           {"4294967296", "does not fit a 32-bit counter"}}) {
    const testing::TempDir dir;
    const std::string path = dir.Write("encoders.csv", header + "2," + ticks + ",0\n");
    try {
      calibration_core::ReadEncodersCsv(path, 32);
      ADD_FAILURE() << ticks << " accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_TRUE(Contains(e.what(), path + ":3: ")) << e.what();
      EXPECT_TRUE(Contains(e.what(), problem)) << e.what();
    }
  }
  const testing::TempDir dir;
  const auto samples =
      calibration_core::ReadEncodersCsv(dir.Write("encoders.csv", header + "2,4294967295,0\n"), 32);
  EXPECT_EQ(samples.back().traction_ticks, 4294967295u);
}

TEST(BadInputCalibration, M6_CalibrateRefusesToWriteOverAnInputAndReportsWriteFailures) {
  const testing::TempDir dir;
  const auto recording = Simulate({});
  const std::string robot = dir.Write("robot.xml", RobotXml());
  const std::string encoders = dir.Write("encoders.csv", recording.encoders_csv);
  const std::string fixes = dir.Write("fixes.csv", recording.fixes_csv);
  auto run = testing::RunCli(
      {"calibrate", "--encoders", encoders, "--fixes", fixes, "--robot", robot, "--out", robot});
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(Contains(run.output, "refusing to write the output over the input")) << run.output;
  EXPECT_EQ(testing::ReadFile(robot), RobotXml());
  run = testing::RunCli({"calibrate", "--encoders", encoders, "--fixes", fixes, "--robot", robot,
                         "--out", "/dev/full"});
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(Contains(run.output, "/dev/full: writing failed")) << run.output;
}

testing::CliResult RunComponent(std::vector<std::string> args) {
  args.insert(args.begin(), {"--domain", std::to_string(testing::domains::kBadInputCalibration),
                             "--qos", testing::SourcePath("qos/structloc_qos.xml")});
  return testing::RunExecutable("structloc_calibration", args, std::chrono::seconds(30));
}

TEST(BadInputCalibration, M6_ComponentRefusesAnOutDirThatIsNotAFolderAtStartUp) {
  const auto run = RunComponent({"--out-dir", "/dev/null", "--record-s", "6", "--exit-when-done"});
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(Contains(run.output, "--out-dir /dev/null exists and is not a folder")) << run.output;
}

// Plays a recording on rt/wheel_encoders and rt/pose (encoders at 20 Hz, all
// fixes, in stamp order) once the component's readers are matched; with
// `as_differential`, the encoder samples claim to be a differential drive's.
void Publish(dds_common::Node& node, const Inputs& inputs, bool as_differential = false) {
  auto encoders = node.CreateWriter<structloc_msgs::msg::WheelEncodersPubSubType>(
      dds_common::topics::kWheelEncoders);
  auto fixes = node.CreateWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      dds_common::topics::kPose);
  ASSERT_TRUE(testing::WaitUntil(
      [&] { return encoders.MatchedReaders() > 0 && fixes.MatchedReaders() > 0; }));
  size_t f = 0;
  for (size_t k = 0; k < inputs.encoders.size(); k += 5) {
    const auto& e = inputs.encoders[k];
    for (; f < inputs.fixes.size() && inputs.fixes[f].t <= e.t; ++f) {
      geometry_msgs::msg::PoseWithCovarianceStamped m;
      m.header().stamp(dds_common::ToRosTime(inputs.fixes[f].t));
      m.pose().pose().position().x(inputs.fixes[f].pose.x);
      m.pose().pose().position().y(inputs.fixes[f].pose.y);
      m.pose().pose().orientation(dds_common::ToQuaternion(inputs.fixes[f].pose.theta));
      m.pose().covariance()[0] = m.pose().covariance()[7] = 1e-4;
      m.pose().covariance()[35] = 1e-4;
      fixes.Write(m);
    }
    structloc_msgs::msg::WheelEncoders m;
    m.header().stamp(dds_common::ToRosTime(e.t));
    m.traction_ticks(e.traction_ticks);
    m.steering_ticks(static_cast<int32_t>(e.steering_ticks));
    if (as_differential) {
      m.differential(true);
      m.left_ticks(e.traction_ticks);
      m.right_ticks(e.traction_ticks);
    }
    encoders.Write(m);
    std::this_thread::sleep_for(std::chrono::microseconds(500));  // paces the publisher
  }
}

constexpr int kComponentDomain = testing::domains::kBadInputCalibration;

// The live calibration component recording for 90 s into `out_dir`.
process::ChildProcess StartRecordingComponent(const std::string& out_dir) {
  return process::ChildProcess(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_calibration",
      {"--domain", std::to_string(kComponentDomain), "--qos", testing::ShippedQos(), "--record-s",
       "90", "--out-dir", out_dir, "--exit-when-done"});
}

bool WaitForRunning(process::ChildProcess& component) {
  return testing::WaitUntil([&] { return Contains(component.CapturedOutput(), "running"); });
}

TEST(BadInputCalibration, M2_ComponentExitsNonZeroWhenTheCalibrationFails) {
  const testing::TempDir dir;
  const auto inputs = Read(dir, Simulate({0, 32, true}));
  auto component = StartRecordingComponent(dir / "out");
  ASSERT_TRUE(WaitForRunning(component)) << component.CapturedOutput();
  dds_common::Node node(testing::TestNodeOptions("recording_player", kComponentDomain));
  Publish(node, inputs);
  const auto code = component.WaitExit(std::chrono::seconds(30));
  ASSERT_TRUE(code.has_value()) << component.CapturedOutput();
  EXPECT_EQ(*code, 1) << component.CapturedOutput();
  EXPECT_TRUE(Contains(component.CapturedOutput(), "traction encoder never changes"))
      << component.CapturedOutput();
  EXPECT_FALSE(Exists(dir / "out/calibrated.xml"));
}

TEST(BadInputCalibration, M6_ComponentExitsNonZeroWhenItsResultCannotBeWritten) {
  const testing::TempDir dir;
  const auto inputs = Read(dir, Simulate({}));
  const std::string out = dir / "out";
  auto component = StartRecordingComponent(out);
  ASSERT_TRUE(WaitForRunning(component)) << component.CapturedOutput();
  // The folder checked at start-up turns into a file before the result is written.
  std::filesystem::remove_all(out);
  dir.Write("out", "not a folder");
  dds_common::Node node(testing::TestNodeOptions("recording_player", kComponentDomain));
  Publish(node, inputs);
  const auto code = component.WaitExit(std::chrono::seconds(30));
  ASSERT_TRUE(code.has_value()) << component.CapturedOutput();
  EXPECT_EQ(*code, 1) << component.CapturedOutput();
  EXPECT_TRUE(Contains(component.CapturedOutput(), "calibration: estimated"))
      << component.CapturedOutput();
  EXPECT_TRUE(Contains(component.CapturedOutput(), "the result could not be written"))
      << component.CapturedOutput();
}

TEST(BadInputCalibration, ComponentRefusesEncodersOfAnotherDriveKindAndKeepsRunning) {
  const testing::TempDir dir;
  const auto inputs = Read(dir, Simulate({}));
  auto component = StartRecordingComponent(dir / "out");
  ASSERT_TRUE(WaitForRunning(component)) << component.CapturedOutput();
  dds_common::Node node(testing::TestNodeOptions("recording_player", kComponentDomain));
  Publish(node, inputs, true);
  EXPECT_TRUE(testing::WaitUntil([&] {
    return Contains(component.CapturedOutput(),
                    "refusing wheel encoders of a differential drive with 0-bit counters: the "
                    "robot file");
  })) << component.CapturedOutput();
  EXPECT_FALSE(component.WaitExit(std::chrono::seconds(1)).has_value())
      << "the component stopped: " << component.CapturedOutput();
  EXPECT_FALSE(Contains(component.CapturedOutput(), "calibration: estimated"));
}

TEST(BadInputCalibration, L1_CounterBitsAreRangeCheckedBeforeNarrowing) {
  const testing::TempDir dir;
  const std::string path =
      dir.Write("robot.xml", RobotXml({{"traction_counter_bits", "4294967328"}}));
  try {
    kinematics::LoadRobotParameters(path);
    ADD_FAILURE() << "traction_counter_bits=4294967328 accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(Contains(e.what(), path + ":2:")) << e.what();
    EXPECT_TRUE(Contains(e.what(), "traction_counter_bits = 4294967328")) << e.what();
  }
}

TEST(BadInputCalibration, L4_ByteOrderMarkBeforeTheHeaderIsAccepted) {
  const testing::TempDir dir;
  const auto encoders = calibration_core::ReadEncodersCsv(
      dir.Write("e.csv", "\xEF\xBB\xBFt,traction_ticks,steering_ticks\n1,0,0\n2,5,0\n"), 32);
  EXPECT_EQ(encoders.size(), 2u);
  const auto fixes = calibration_core::ReadFixesCsv(
      dir.Write("f.csv", "\xEF\xBB\xBFt,x,y,theta\n1,0,0,0\n2,1,0,0\n3,2,0,0\n"));
  EXPECT_EQ(fixes.fixes.size(), 3u);
}

TEST(BadInputCalibration, L4_InfiniteAndNegativeVariancesAreNamedAsSuch) {
  const testing::TempDir dir;
  const auto file = calibration_core::ReadFixesCsv(
      dir.Write("f.csv",
                "t,x,y,theta,var_x,var_y,var_theta\n1,0,0,0,1,1,1\n2,1,0,0,inf,1,1\n"
                "3,2,0,0,1,-1,1\n4,3,0,0,1,1,1\n5,nan,0,0,1,1,1\n6,4,0,0,1,1,1\n"));
  EXPECT_EQ(file.fixes.size(), 3u);
  EXPECT_EQ(calibration_core::DescribeDropped(file),
            "3 dropped (1 with NaN, 1 with an infinite value, 1 with a negative variance; "
            "first at line 3)");
}

TEST(BadInputCalibration, L4_HugeValuesAreNotPrintedWithHundredsOfDigits) {
  const testing::TempDir dir;
  auto recording = Simulate({});
  // The last fix absurdly far away: the run fails, but every number stays readable.
  const size_t last_line = recording.fixes_csv.rfind('\n', recording.fixes_csv.size() - 2) + 1;
  const size_t x = recording.fixes_csv.find(',', last_line) + 1;
  recording.fixes_csv.replace(x, recording.fixes_csv.find(',', x) - x, "1e150");
  const auto run = RunCalibrate(dir, recording, RobotXml());
  EXPECT_NE(run.cli.exit_code, 0) << run.cli.output;
  EXPECT_FALSE(std::regex_search(run.cli.output, std::regex("[0-9]{30}"))) << run.cli.output;
  // ... and the message names the line with the impossible position.
  EXPECT_TRUE(std::regex_search(run.cli.output,
                                std::regex(":[0-9]+: position \\(1e150, .*more than 100 km")))
      << run.cli.output;
}

TEST(BadInputCalibration, L8_RobotFileCommentStaysWellFormedWithDoubleHyphenPaths) {
  const testing::TempDir dir;
  const auto recording = Simulate({});
  const std::string encoders = dir.Write("run--1.csv", recording.encoders_csv);
  const std::string fixes = dir.Write("fixes--.csv", recording.fixes_csv);
  const std::string robot = dir.Write("robot.xml", RobotXml());
  const std::string out = dir / "calibrated.xml";
  const auto run = testing::RunCli(
      {"calibrate", "--encoders", encoders, "--fixes", fixes, "--robot", robot, "--out", out});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string xml = testing::ReadFile(out);
  const size_t open = xml.find("<!--"), close = xml.find("-->");
  ASSERT_NE(open, std::string::npos);
  ASSERT_NE(close, std::string::npos);
  const std::string body = xml.substr(open + 4, close - open - 4);
  EXPECT_FALSE(Contains(body, "--")) << body;
  EXPECT_NE(body.back(), '-') << body;
  EXPECT_EQ(kinematics::XmlCommentBody("a---b-"), "a- - -b- ");
}

TEST(BadInputCalibration, L9_ComponentRefusesMeaninglessOptions) {
  for (const auto& [option, value, problem] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"--fix-topic", "", "--fix-topic is empty"},
           {"--fix-topic", "rt/scan", "--fix-topic rt/scan is a structloc topic of another"},
           {"--fix-topic", "rt/my pose", "contains a space"},
           {"--estimate", "", "--estimate is empty"},
           {"--estimate", "wheel_radius,", "empty parameter name"}}) {
    const auto run = RunComponent({option, value});
    EXPECT_EQ(run.exit_code, 2) << option << " '" << value << "'\n" << run.output;
    EXPECT_TRUE(Contains(run.output, problem)) << run.output;
  }
}

TEST(BadInputCalibration, L9_CalibrateRefusesAnEmptyEstimateList) {
  const testing::TempDir dir;
  const auto run = RunCalibrate(dir, Simulate({}), RobotXml(), {"--estimate", ""});
  EXPECT_EQ(run.cli.exit_code, 2) << run.cli.output;
  EXPECT_TRUE(Contains(run.cli.output, "--estimate is empty")) << run.cli.output;
}

}  // namespace
}  // namespace structloc
