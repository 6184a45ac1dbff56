// PeerMonitor (see header).
#include "structloc/dds_common/peer_monitor.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>

#include <iostream>
#include <sstream>

namespace structloc::dds_common {

using eprosima::fastdds::dds::QosPolicyId_t;

const char* QosPolicyName(QosPolicyId_t policy) {
  using namespace eprosima::fastdds::dds;
  switch (policy) {
    case DURABILITY_QOS_POLICY_ID:
      return "DURABILITY";
    case DEADLINE_QOS_POLICY_ID:
      return "DEADLINE";
    case LIVELINESS_QOS_POLICY_ID:
      return "LIVELINESS";
    case OWNERSHIP_QOS_POLICY_ID:
      return "OWNERSHIP";
    case RELIABILITY_QOS_POLICY_ID:
      return "RELIABILITY";
    case DESTINATIONORDER_QOS_POLICY_ID:
      return "DESTINATION_ORDER";
    case PARTITION_QOS_POLICY_ID:
      return "PARTITION";
    case DATAREPRESENTATION_QOS_POLICY_ID:
      return "DATA_REPRESENTATION";
    case DISABLEPOSITIVEACKS_QOS_POLICY_ID:
      return "DISABLE_POSITIVE_ACKS";
    default:
      return "another policy";
  }
}

PeerMonitor::PeerMonitor(std::string node_name, int domain_id)
    : node_name_(std::move(node_name)), domain_id_(domain_id) {}

void PeerMonitor::Report(const std::string& key, const std::string& message) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (problems_.emplace(key, message).second) {
    std::cerr << node_name_ << ": WARNING: " << message << std::endl;
  }
}

void PeerMonitor::IncompatibleQos(const std::string& topic, const char* role,
                                  QosPolicyId_t policy) {
  const std::string name = QosPolicyName(policy);
  Report("qos " + topic + " " + name,
         std::string(role) + " on " + topic + " cannot match a peer: incompatible " + name +
             " QoS (no data flows between them; check both QoS profiles)");
}

void PeerMonitor::on_participant_discovery(
    eprosima::fastdds::dds::DomainParticipant* participant,
    eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) {
  using Status = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo::DISCOVERY_STATUS;
  if (info.info.m_guid.guidPrefix == participant->guid().guidPrefix) return;
  if (std::string(info.info.m_participantName.c_str()) != node_name_) return;
  std::ostringstream guid;
  guid << info.info.m_guid.guidPrefix;
  const std::string key = "duplicate " + guid.str();
  if (info.status == Status::DISCOVERED_PARTICIPANT) {
    Report(key, "another participant named '" + node_name_ + "' is on domain " +
                    std::to_string(domain_id_) + " (GUID prefix " + guid.str() +
                    "): two instances of this component interleave their outputs; stop one or "
                    "give it another domain or namespace");
  } else if (info.status == Status::REMOVED_PARTICIPANT ||
             info.status == Status::DROPPED_PARTICIPANT) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (problems_.erase(key) > 0) {
      std::cerr << node_name_ << ": the other participant named '" << node_name_ << "' has left"
                << std::endl;
    }
  }
}

std::vector<std::string> PeerMonitor::Problems() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> out;
  for (const auto& [key, message] : problems_) out.push_back(message);
  return out;
}

}  // namespace structloc::dds_common
