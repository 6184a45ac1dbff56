// DDS Security keeps strangers out (issue 16): with a keystore made by the
// shipped structloc_keystore, real Fast DDS participants show that an
// unauthenticated writer of rt/scan or rt/initialpose gets none of 1000
// samples accepted, that an authenticated identity cannot create a writer or
// reader its permissions do not grant, that a certificate from another CA with
// the same subject is never matched, and that a component given a missing or
// broken enclave refuses to start, naming the file, and that a QoS profile
// cannot switch security off (a hostile dds.sec.* property is refused by the
// component, by structloc_check_qos and by every node given a keystore,
// whatever file Fast DDS read it from). Each check has a positive
// control (the granted identity does get its samples through), so none can
// pass because nothing was connected.
#include <gtest/gtest.h>
#include <unistd.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"
#include "dds_test_support.hpp"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "structloc/config/command_line.hpp"
#include "structloc/process/child_process.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
using ScanType = sensor_msgs::msg::LaserScanPubSubType;
using PoseType = geometry_msgs::msg::PoseWithCovarianceStampedPubSubType;
constexpr int kDomain = testing::domains::kDdsSecurity;
constexpr int kSamples = 1000;

// Makes a keystore with the shipped script; empty string on failure.
std::string MakeKeystore(const testing::TempDir& dir, const std::string& name) {
  const std::string keystore = dir / name;
  const std::string command = std::string(STRUCTLOC_BIN_DIR) + "/structloc_keystore '" + keystore +
                              "' > '" + keystore + ".log' 2>&1";
  return std::system(command.c_str()) == 0 ? keystore : "";
}

dds_common::NodeOptions SecureOptions(const std::string& name, const std::string& keystore,
                                      const std::string& identity) {
  auto options = testing::TestNodeOptions(name, kDomain);
  options.security = {keystore, identity};
  return options;
}

// Counts the samples of one topic by the frame id their writer stamped.
class Counter {
 public:
  std::atomic<int> stranger{0};
  std::atomic<int> granted{0};
  void Count(const std::string& frame_id) {
    if (frame_id == "stranger") ++stranger;
    if (frame_id == "granted") ++granted;
  }
};

sensor_msgs::msg::LaserScan Scan(const std::string& frame_id) {
  sensor_msgs::msg::LaserScan scan;
  scan.header().frame_id(frame_id);
  scan.angle_min(-1.0f);
  scan.angle_max(1.0f);
  scan.angle_increment(0.5f);
  scan.range_min(0.1f);
  scan.range_max(10.0f);
  scan.ranges({1.0f, 1.0f, 1.0f, 1.0f, 1.0f});
  return scan;
}

geometry_msgs::msg::PoseWithCovarianceStamped Pose(const std::string& frame_id) {
  geometry_msgs::msg::PoseWithCovarianceStamped pose;
  pose.header().frame_id(frame_id);
  pose.pose().pose().orientation().w(1.0);
  return pose;
}

// Writes `count` samples, one every millisecond.
template <class Writer, class Message>
void WriteMany(Writer& writer, const Message& message, int count) {
  for (int i = 0; i < count; ++i) {
    writer.Write(message);
    std::this_thread::sleep_for(1ms);
  }
}

class DdsSecurity : public ::testing::Test {
 protected:
  void SetUp() override {
    keystore_ = MakeKeystore(dir_, "keystore");
    ASSERT_FALSE(keystore_.empty()) << "structloc_keystore failed: see " << dir_.Path();
  }
  testing::TempDir dir_;
  std::string keystore_;
};

TEST_F(DdsSecurity, AnUnauthenticatedWriterGetsNoSampleAccepted) {
  dds_common::Node localisation(SecureOptions("localisation", keystore_, "localisation"));
  Counter scans, poses;
  const auto scan_subscription = localisation.Subscribe<ScanType>(
      dds_common::topics::kScan, [&](const auto& s) { scans.Count(s.header().frame_id()); });
  const auto pose_subscription = localisation.Subscribe<PoseType>(
      dds_common::topics::kInitialPose, [&](const auto& p) { poses.Count(p.header().frame_id()); });

  {
    dds_common::Node stranger(testing::TestNodeOptions("stranger", kDomain));
    auto scan_writer = stranger.CreateWriter<ScanType>(dds_common::topics::kScan);
    auto pose_writer = stranger.CreateWriter<PoseType>(dds_common::topics::kInitialPose);
    std::this_thread::sleep_for(2s);  // time to discover, had it been allowed to
    EXPECT_EQ(scan_writer.MatchedReaders(), 0u);
    EXPECT_EQ(pose_writer.MatchedReaders(), 0u);
    WriteMany(scan_writer, Scan("stranger"), kSamples);
    WriteMany(pose_writer, Pose("stranger"), kSamples);
    std::this_thread::sleep_for(1s);
  }

  // The controls: the granted identities on the same topics do get through.
  dds_common::Node simulator(SecureOptions("simulator", keystore_, "simulator"));
  dds_common::Node operator_node(SecureOptions("operator", keystore_, "operator"));
  auto scan_writer = simulator.CreateWriter<ScanType>(dds_common::topics::kScan);
  auto pose_writer = operator_node.CreateWriter<PoseType>(dds_common::topics::kInitialPose);
  ASSERT_TRUE(testing::WaitUntil([&] {
    return scan_writer.MatchedReaders() > 0 && pose_writer.MatchedReaders() > 0;
  })) << "the granted identities never matched: the test proves nothing";
  ASSERT_TRUE(testing::WaitUntil([&] {
    scan_writer.Write(Scan("granted"));
    pose_writer.Write(Pose("granted"));
    return scans.granted > 0 && poses.granted > 0;
  }));
  EXPECT_EQ(scans.stranger, 0) << "of " << kSamples << " unauthenticated scans";
  EXPECT_EQ(poses.stranger, 0) << "of " << kSamples << " unauthenticated initial poses";
  std::printf("unauthenticated: %d of %d scans and %d of %d initial poses accepted\n",
              scans.stranger.load(), kSamples, poses.stranger.load(), kSamples);
}

TEST_F(DdsSecurity, AnIdentityWithoutTheGrantCannotCreateTheEndpoint) {
  dds_common::Node localisation(SecureOptions("localisation", keystore_, "localisation"));
  dds_common::Node operator_node(SecureOptions("operator", keystore_, "operator"));
  dds_common::Node calibration(SecureOptions("calibration", keystore_, "calibration"));
  // Only the simulator (or laser driver) may publish scans, only the
  // localisation poses, only the operator initial poses.
  EXPECT_THROW(localisation.CreateWriter<ScanType>(dds_common::topics::kScan), std::runtime_error);
  EXPECT_THROW(operator_node.CreateWriter<PoseType>(dds_common::topics::kPose), std::runtime_error);
  EXPECT_THROW(calibration.CreateWriter<PoseType>(dds_common::topics::kInitialPose),
               std::runtime_error);
  EXPECT_THROW(
      {
        const auto subscription =
            calibration.Subscribe<ScanType>(dds_common::topics::kScan, [](const auto&) {});
      },
      std::runtime_error);
  // What each is granted it can create.
  EXPECT_NO_THROW(localisation.CreateWriter<PoseType>(dds_common::topics::kPose));
  EXPECT_NO_THROW(operator_node.CreateWriter<PoseType>(dds_common::topics::kInitialPose));
}

TEST_F(DdsSecurity, ACertificateFromAnotherCaWithTheSameSubjectIsNeverMatched) {
  const std::string impostor_keystore = MakeKeystore(dir_, "impostor");
  ASSERT_FALSE(impostor_keystore.empty());
  dds_common::Node localisation(SecureOptions("localisation", keystore_, "localisation"));
  Counter scans;
  const auto subscription = localisation.Subscribe<ScanType>(
      dds_common::topics::kScan, [&](const auto& s) { scans.Count(s.header().frame_id()); });
  {
    // Same subject (CN=simulator, O=structloc, C=CH), same grants, other CA.
    dds_common::Node impostor(SecureOptions("simulator", impostor_keystore, "simulator"));
    auto writer = impostor.CreateWriter<ScanType>(dds_common::topics::kScan);
    std::this_thread::sleep_for(3s);
    EXPECT_EQ(writer.MatchedReaders(), 0u);
    WriteMany(writer, Scan("stranger"), kSamples);
  }
  dds_common::Node simulator(SecureOptions("simulator", keystore_, "simulator"));
  auto writer = simulator.CreateWriter<ScanType>(dds_common::topics::kScan);
  ASSERT_TRUE(testing::WaitUntil([&] {
    writer.Write(Scan("granted"));
    return scans.granted > 0;
  })) << "the genuine simulator never got through: the test proves nothing";
  EXPECT_EQ(scans.stranger, 0) << "of " << kSamples << " scans under the other CA's certificate";
}

TEST_F(DdsSecurity, AMissingOrBrokenEnclaveFileStopsTheNodeNamingIt) {
  const std::string enclave = keystore_ + "/enclaves/localisation";
  std::filesystem::remove(enclave + "/key.pem");
  try {
    dds_common::Node node(SecureOptions("localisation", keystore_, "localisation"));
    FAIL() << "a node started without its private key";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(enclave + "/key.pem"), std::string::npos) << e.what();
  }
  try {
    dds_common::Node node(SecureOptions("nobody", keystore_, "nobody"));
    FAIL() << "a node started with an enclave that does not exist";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("enclaves/nobody"), std::string::npos) << e.what();
  }
  // A certificate that is not one: Fast DDS refuses, the node says so.
  std::ofstream(keystore_ + "/enclaves/simulator/cert.pem") << "not a certificate\n";
  try {
    dds_common::Node node(SecureOptions("simulator", keystore_, "simulator"));
    FAIL() << "a node started with a broken certificate";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("DDS Security refused the enclave"), std::string::npos)
        << e.what();
  }
}

TEST_F(DdsSecurity, AComponentWithoutItsEnclaveRefusesToStart) {
  std::filesystem::remove(keystore_ + "/enclaves/localisation/permissions.p7s");
  process::ChildProcess localisation(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--security-keystore",
       keystore_, "--initial-pose", "2 6.5 0"});
  const auto code = localisation.WaitExit(30s);
  ASSERT_TRUE(code.has_value()) << "it kept running: " << localisation.CapturedOutput();
  EXPECT_EQ(*code, 2);
  EXPECT_NE(localisation.CapturedOutput().find("permissions.p7s"), std::string::npos)
      << localisation.CapturedOutput();
}

// The shipped QoS file with a participant property that names another
// authentication plugin: Fast DDS takes the first property of a name, and
// one of the profile's came before the enclave's.
std::string HostileQos(const testing::TempDir& dir) {
  std::string text = testing::ReadFile(testing::ShippedQos());
  const auto rtps = text.find("<rtps>");
  if (rtps == std::string::npos) return "";
  text.insert(rtps + 6,
              "<propertiesPolicy><properties><property><name>dds.sec.auth.plugin</name>"
              "<value>none</value></property></properties></propertiesPolicy>");
  return dir.Write("qos_tampered.xml", text);
}

TEST_F(DdsSecurity, AProfileThatSwitchesSecurityOffIsRefusedEverywhere) {
  const std::string hostile = HostileQos(dir_);
  ASSERT_FALSE(hostile.empty());
  const std::string problem = "sets DDS Security from --security-keystore alone";

  // The component given a keystore refuses to start, naming file, line and property.
  const auto component =
      testing::RunExecutable("structloc_localisation",
                             {"--domain", std::to_string(kDomain), "--qos", hostile,
                              "--security-keystore", keystore_, "--initial-pose", "2 6.5 0"},
                             30s);
  EXPECT_EQ(component.exit_code, 2) << component.output;
  EXPECT_NE(component.output.find(hostile + ":"), std::string::npos) << component.output;
  EXPECT_NE(component.output.find("dds.sec.auth.plugin"), std::string::npos) << component.output;
  EXPECT_NE(component.output.find(problem), std::string::npos) << component.output;

  // structloc_check_qos reports the same, and passes the shipped file (control).
  const auto check = testing::RunExecutable("structloc_check_qos", {hostile});
  EXPECT_EQ(check.exit_code, 2) << check.output;
  EXPECT_NE(check.output.find("dds.sec.auth.plugin"), std::string::npos) << check.output;
  EXPECT_EQ(testing::RunExecutable("structloc_check_qos", {testing::ShippedQos()}).exit_code, 0);

  // A profile of the same name that Fast DDS read before ours (as it reads a
  // DEFAULT_FASTRTPS_PROFILES.xml in the working folder) cannot slip in
  // either: Fast DDS keeps the first and only logs that ours was not added.
  const std::string name = "structloc_hostile_" + std::to_string(::getpid());
  const std::string elsewhere = dir_.Write(
      "elsewhere.xml",
      "<?xml version=\"1.0\"?><dds><profiles xmlns=\"http://www.eprosima.com/XMLSchemas/"
      "fastRTPS_Profiles\"><participant profile_name=\"" +
          name +
          "\"><rtps>"
          "<propertiesPolicy><properties><property><name>dds.sec.auth.plugin</name><value>none"
          "</value></property></properties></propertiesPolicy></rtps></participant></profiles></"
          "dds>");
  ASSERT_EQ(
      eprosima::fastdds::dds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(
          elsewhere),
      eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK);
  std::string clean = testing::ReadFile(testing::ShippedQos());
  const std::string shipped_name = "profile_name=\"structloc_localhost\"";
  clean.replace(clean.find(shipped_name), shipped_name.size(), "profile_name=\"" + name + "\"");
  auto options = SecureOptions("localisation", keystore_, "localisation");
  options.qos_file = dir_.Write("clean_copy.xml", clean);
  options.participant_profile = name;
  try {
    dds_common::Node node(options);
    ADD_FAILURE() << "a node ran with a profile that switches DDS Security off";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace structloc
