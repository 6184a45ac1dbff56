// What a node notices about its peers that a user must hear about, because DDS
// itself stays silent: a reader or writer whose QoS cannot match a peer's (no
// data will ever flow), and another participant with this node's own name on
// the same domain (two instances of one component interleave their outputs).
// Each problem is logged once as it appears and kept while it lasts, for the
// component's diagnostics.
#pragma once

#include <fastdds/dds/core/status/IncompatibleQosStatus.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace structloc::dds_common {

class PeerMonitor : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  PeerMonitor(std::string node_name, int domain_id);

  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;

  // Called by the node's reader and writer listeners.
  void IncompatibleQos(const std::string& topic, const char* role,
                       eprosima::fastdds::dds::QosPolicyId_t policy);

  // The problems that currently hold, one sentence each.
  std::vector<std::string> Problems() const;

 private:
  void Report(const std::string& key, const std::string& message);

  std::string node_name_;
  int domain_id_;
  mutable std::mutex mutex_;
  std::map<std::string, std::string> problems_;  // key -> message
};

// "RELIABILITY", "DURABILITY", ... for a QoS policy id.
const char* QosPolicyName(eprosima::fastdds::dds::QosPolicyId_t policy);

}  // namespace structloc::dds_common
