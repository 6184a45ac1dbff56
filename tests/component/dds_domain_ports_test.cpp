// Why DDS tests and deployments keep to domain ids 0..101 (the flaky-test
// issue): on Linux any process's outgoing UDP socket gets a random port from
// the ephemeral range (32768-60999), which contains every port of the domains
// above 101, and a participant that relies on multicast discovery
// (structloc_network, Fast DDS's defaults) is cut off from its peers when its
// discovery port is held. The first test shows that the default profile's
// unicast discovery survives a held port; the others show that no safe domain
// can be hit at all, and that the components warn about a domain that can.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "dds_test_support.hpp"
#include "std_msgs/msg/HeaderPubSubTypes.h"
#include "structloc/dds_common/domain_ports.hpp"
#include "test_domains.hpp"

namespace structloc {
namespace {

constexpr int kDomain = testing::domains::kDomainPorts;

// A plain UDP socket on `port` of every interface, as the kernel gives an
// outgoing socket of any program; closed when it goes out of scope.
class HeldPort {
 public:
  explicit HeldPort(int port) : fd_(socket(AF_INET, SOCK_DGRAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_ANY);
    bound_ = bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;
  }
  ~HeldPort() { close(fd_); }
  bool Bound() const { return bound_; }

 private:
  int fd_;
  bool bound_ = false;
};

std::optional<std::string> RoundTripOnce(int domain) {
  dds_common::Node writer(testing::TestNodeOptions("ports_writer", domain));
  dds_common::Node reader(testing::TestNodeOptions("ports_reader", domain));
  std_msgs::msg::Header sample;
  sample.frame_id("probe");
  auto received = testing::RoundTrip<std_msgs::msg::HeaderPubSubType>(
      writer, reader, {"rt/structloc/port_probe", "reliable_state"}, sample);
  if (!received) return std::nullopt;
  return received->frame_id();
}

// The default profile announces participants to 127.0.0.1's unicast ports of
// participants 0..99, so one held port (the domain's multicast discovery port,
// or the first participant's unicast one) no longer cuts them off: the
// participants take the next free ports and still meet.
TEST(DdsDomainPorts, TheDefaultProfileSurvivesASocketHoldingADiscoveryPort) {
  const int multicast_port = dds_common::DomainPortRange(kDomain).first;
  for (const int port : {multicast_port, multicast_port + 10}) {
    HeldPort held(port);
    ASSERT_TRUE(held.Bound()) << "port " << port << " is busy already";
    EXPECT_EQ(RoundTripOnce(kDomain).value_or("nothing"), "probe")
        << "participants did not meet while port " << port << " was held";
  }
}

TEST(DdsDomainPorts, SafeDomainsStayBelowTheEphemeralRange) {
  const auto ephemeral = dds_common::EphemeralPortRange();
  ASSERT_TRUE(ephemeral.has_value());
  std::printf("ephemeral ports here: %d-%d\n", ephemeral->first, ephemeral->second);
  for (int domain = 0; domain <= dds_common::kMaxSafeDomainId; ++domain) {
    EXPECT_FALSE(dds_common::DomainPortWarning(domain, std::make_pair(32768, 60999)).has_value())
        << domain;
  }
  for (int domain : testing::domains::kAll) {
    EXPECT_LT(dds_common::DomainPortRange(domain).second, ephemeral->first) << domain;
  }
}

TEST(DdsDomainPorts, DomainsInTheEphemeralRangeAreWarnedAbout) {
  for (int domain : {102, 110, 150, 214}) {
    const auto warning = dds_common::DomainPortWarning(domain, std::make_pair(32768, 60999));
    ASSERT_TRUE(warning.has_value()) << domain;
    EXPECT_NE(warning->find("0..101"), std::string::npos) << *warning;
  }
  EXPECT_EQ(dds_common::DomainPortRange(110).first, 34900);
  EXPECT_FALSE(dds_common::DomainPortWarning(232, std::make_pair(32768, 60999)).has_value());
}

}  // namespace
}  // namespace structloc
