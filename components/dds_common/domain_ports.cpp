// Domain port arithmetic and the ephemeral-range check (see header).
#include "structloc/dds_common/domain_ports.hpp"

#include <fstream>

namespace structloc::dds_common {

std::pair<int, int> DomainPortRange(int domain_id) {
  const int base = 7400 + kPortsPerDomain * domain_id;
  return {base, base + 11 + 2 * (kParticipantsPerHost - 1)};
}

std::optional<std::pair<int, int>> EphemeralPortRange(const std::string& proc_file) {
  std::ifstream in(proc_file);
  int low = 0, high = 0;
  if (!(in >> low >> high) || low <= 0 || high < low) return std::nullopt;
  return std::make_pair(low, high);
}

std::optional<std::string> DomainPortWarning(int domain_id,
                                             const std::optional<std::pair<int, int>>& ephemeral) {
  const auto [first, last] = DomainPortRange(domain_id);
  const int low = ephemeral ? ephemeral->first : 32768;
  const int high = ephemeral ? ephemeral->second : 60999;
  if (last < low || first > high) return std::nullopt;
  return "domain " + std::to_string(domain_id) + " uses UDP ports " + std::to_string(first) + "-" +
         std::to_string(last) + ", inside this machine's ephemeral port range " +
         std::to_string(low) + "-" + std::to_string(high) +
         ": any process's outgoing socket may hold one and silently cut this participant off "
         "its peers. Use a domain id of 0.." +
         std::to_string(kMaxSafeDomainId) + ".";
}

}  // namespace structloc::dds_common
