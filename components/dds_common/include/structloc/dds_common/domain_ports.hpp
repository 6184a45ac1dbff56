// Which UDP ports a DDS domain uses (RTPS port mapping: 7400 + 250 x domain +
// offsets) and whether they fall into Linux's ephemeral port range, where any
// process's outgoing socket may already hold one: a participant that cannot
// bind its discovery port is deaf to its peers. Domain ids 0..101 stay below
// the default range (32768-60999); higher ids are legal but unreliable.
#pragma once

#include <optional>
#include <string>
#include <utility>

namespace structloc::dds_common {

constexpr int kMaxDomainId = 232;         // the RTPS port mapping's upper limit
constexpr int kMaxSafeDomainId = 101;     // below Linux's default ephemeral ports
constexpr int kPortsPerDomain = 250;      // RTPS "domain id gain"
constexpr int kParticipantsPerHost = 50;  // participants of one domain on one host we plan for

// [first, last] UDP port the first kParticipantsPerHost participants of a
// domain on one host use: discovery and user multicast (base, base + 1) and
// each participant's two unicast ports (base + 10 + 2 id, base + 11 + 2 id).
std::pair<int, int> DomainPortRange(int domain_id);

// The machine's ephemeral port range, read from `proc_file`
// (/proc/sys/net/ipv4/ip_local_port_range); nullopt when unreadable.
std::optional<std::pair<int, int>> EphemeralPortRange(
    const std::string& proc_file = "/proc/sys/net/ipv4/ip_local_port_range");

// A warning when the domain's ports overlap the ephemeral range, else nullopt.
std::optional<std::string> DomainPortWarning(
    int domain_id, const std::optional<std::pair<int, int>>& ephemeral = EphemeralPortRange());

}  // namespace structloc::dds_common
