// The shipped QoS profiles load through the same code the components use and
// carry the values we rely on; broken files are rejected with file and problem.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <regex>
#include <thread>
#include <vector>

#include "dds_test_support.hpp"
#include "structloc/dds_common/qos_profiles.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

namespace structloc {
namespace {

using eprosima::fastdds::dds::BEST_EFFORT_RELIABILITY_QOS;
using eprosima::fastdds::dds::KEEP_LAST_HISTORY_QOS;
using eprosima::fastdds::dds::RELIABLE_RELIABILITY_QOS;
using eprosima::fastdds::dds::TRANSIENT_LOCAL_DURABILITY_QOS;
using eprosima::fastdds::dds::VOLATILE_DURABILITY_QOS;

constexpr int kDomain = testing::domains::kQosProfiles;

TEST(QosProfiles, ShippedFileHasTheProfilesAndValuesWeRelyOn) {
  dds_common::Node node(testing::TestNodeOptions("qos_test", kDomain));  // loads the file
  const auto qos = dds_common::QosProfiles::Load(testing::ShippedQos());
  for (const auto* name : {"structloc_localhost", "structloc_network"}) {
    const auto pq = qos.Participant(name);
    EXPECT_EQ(pq.wire_protocol().builtin.discovery_config.leaseDuration.seconds, 3) << name;
  }
  // UDPv4 only: Fast DDS 2.9's shared-memory transport can leave a participant
  // that joins while another on the host leaves deaf to every peer (the flaky
  // calibration test failed that way about one run in three).
  for (const auto* name : {"structloc_localhost", "structloc_network"}) {
    const auto pq = qos.Participant(name);
    EXPECT_FALSE(pq.transport().use_builtin_transports) << name;
    ASSERT_EQ(pq.transport().user_transports.size(), 1u) << name;
    EXPECT_NE(std::dynamic_pointer_cast<eprosima::fastdds::rtps::UDPv4TransportDescriptor>(
                  pq.transport().user_transports.front()),
              nullptr)
        << name;
  }
  const auto localhost = qos.Participant("structloc_localhost");

  // Build a throwaway participant to read writer/reader profiles through Fast DDS.
  auto* factory = eprosima::fastdds::dds::DomainParticipantFactory::get_instance();
  auto* participant = factory->create_participant(kDomain, localhost);
  ASSERT_NE(participant, nullptr);
  auto* pub = participant->create_publisher(eprosima::fastdds::dds::PUBLISHER_QOS_DEFAULT);
  auto* sub = participant->create_subscriber(eprosima::fastdds::dds::SUBSCRIBER_QOS_DEFAULT);
  struct Expected {
    const char* profile;
    eprosima::fastdds::dds::ReliabilityQosPolicyKind reliability;
    eprosima::fastdds::dds::DurabilityQosPolicyKind durability;
    int depth;
  };
  for (const auto& e :
       {Expected{"sensor_data", BEST_EFFORT_RELIABILITY_QOS, VOLATILE_DURABILITY_QOS, 5},
        Expected{"reliable_state", RELIABLE_RELIABILITY_QOS, VOLATILE_DURABILITY_QOS, 100},
        Expected{"latched_result", RELIABLE_RELIABILITY_QOS, TRANSIENT_LOCAL_DURABILITY_QOS, 1}}) {
    const auto w = qos.Writer(*pub, e.profile);
    const auto r = qos.Reader(*sub, e.profile);
    EXPECT_EQ(w.reliability().kind, e.reliability) << e.profile;
    EXPECT_EQ(r.reliability().kind, e.reliability) << e.profile;
    EXPECT_EQ(w.durability().kind, e.durability) << e.profile;
    EXPECT_EQ(r.durability().kind, e.durability) << e.profile;
    EXPECT_EQ(w.history().kind, KEEP_LAST_HISTORY_QOS) << e.profile;
    EXPECT_EQ(w.history().depth, e.depth) << e.profile;
    EXPECT_EQ(r.history().depth, e.depth) << e.profile;
    // No /dev/shm segment a killed process could leave behind.
    EXPECT_EQ(w.data_sharing().kind(), eprosima::fastdds::dds::OFF) << e.profile;
    EXPECT_EQ(r.data_sharing().kind(), eprosima::fastdds::dds::OFF) << e.profile;
  }
  // A lost state sample is asked for again within 50 ms (the packet-loss test).
  const auto state_writer = qos.Writer(*pub, "reliable_state");
  EXPECT_EQ(state_writer.reliable_writer_qos().times.heartbeatPeriod.seconds, 0);
  EXPECT_EQ(state_writer.reliable_writer_qos().times.heartbeatPeriod.nanosec, 50000000u);
  EXPECT_THROW(qos.Writer(*pub, "no_such_profile"), dds_common::QosError);
  participant->delete_contained_entities();
  factory->delete_participant(participant);
}

// Writes a copy of the shipped file with one substitution applied.
std::string BrokenCopy(const testing::TempDir& temp, const std::string& tag,
                       const std::string& from, const std::string& to) {
  std::ifstream in(testing::ShippedQos());
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const auto pos = text.find(from);
  if (pos == std::string::npos) throw std::runtime_error("pattern not in shipped file: " + from);
  text.replace(pos, from.size(), to);
  return temp.Write("broken_" + tag + ".xml", text);
}

struct BrokenCase {
  const char* tag;
  const char* from;
  const char* to;
  const char* expected_problem;
};

class BrokenQos : public ::testing::TestWithParam<BrokenCase> {};

TEST_P(BrokenQos, IsRejectedNamingFileLineAndProblem) {
  const auto& c = GetParam();
  const testing::TempDir temp;
  const std::string path = BrokenCopy(temp, c.tag, c.from, c.to);
  try {
    dds_common::QosProfiles::Load(path);
    ADD_FAILURE() << "a broken profile file was accepted: " << c.tag;
  } catch (const dds_common::QosError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(c.expected_problem), std::string::npos) << what;
    EXPECT_TRUE(std::regex_search(what, std::regex(":[0-9]+:"))) << "no line number: " << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BrokenQos,
    ::testing::Values(
        BrokenCase{"depth0", "<depth>5</depth>", "<depth>0</depth>", "history depth '0'"},
        BrokenCase{"depthneg", "<depth>100</depth>", "<depth>-3</depth>", "history depth '-3'"},
        BrokenCase{"sharing", "<kind>OFF</kind>", "<kind>OF</kind>", "unknown data_sharing kind"},
        BrokenCase{"kind", "<kind>BEST_EFFORT</kind>", "<kind>BEST_EFORT</kind>",
                   "unknown reliability kind"},
        BrokenCase{"duration", "<sec>3</sec>", "<sec>-1</sec>", "duration '-1'"},
        BrokenCase{"malformed", "</participant>", "</participnt>", "malformed XML"},
        BrokenCase{"duplicate", "profile_name=\"structloc_network\"",
                   "profile_name=\"structloc_localhost\"", "duplicate profile"},
        // DDS Security comes from --security-keystore alone: a profile's own
        // dds.sec.* property would stand before the enclave's and win.
        BrokenCase{"security_off", "<rtps>",
                   "<rtps><propertiesPolicy><properties><property><name>dds.sec.auth.plugin"
                   "</name><value>none</value></property></properties></propertiesPolicy>",
                   "property 'dds.sec.auth.plugin' configures DDS Security"},
        BrokenCase{"security_files", "<rtps>",
                   "<rtps><propertiesPolicy><properties><property><name> DDS.SEC.auth.builtin."
                   "PKI-DH.identity_ca</name><value>file:///tmp/ca.pem</value></property>"
                   "</properties></propertiesPolicy>",
                   "configures DDS Security"}),
    [](const auto& info) { return std::string(info.param.tag); });

// Nodes made side by side in one process (the repeated-faults test makes
// three at once) load and read the profiles and create participants from
// several threads: Fast DDS 2.9 keeps the profiles in tables it does not
// lock, and unguarded that aborted the test process once in CI.
TEST(QosProfiles, NodesMadeSideBySideInOneProcess) {
  std::vector<std::thread> threads;
  std::atomic<int> made{0};
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&made, t] {
      for (int i = 0; i < 3; ++i) {
        dds_common::Node node(
            testing::TestNodeOptions("side_by_side_" + std::to_string(t), kDomain));
        dds_common::QosProfiles::Load(testing::ShippedQos()).Participant("structloc_localhost");
        ++made;
      }
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(made.load(), 4 * 3);
}

TEST(QosProfiles, MissingFileIsAnError) {
  EXPECT_THROW(dds_common::QosProfiles::Load("/nonexistent/structloc_qos.xml"),
               dds_common::QosError);
}

}  // namespace
}  // namespace structloc
