// Node: participant creation from a validated QoS file, and clean teardown.
#include "structloc/dds_common/node.hpp"

#include <fastrtps/config.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include <algorithm>
#include <iostream>
#include <sstream>

#include "structloc/config/strict_xml.hpp"
#include "structloc/dds_common/domain_ports.hpp"

namespace structloc::dds_common {

Node::Node(const NodeOptions& options)
    : options_(options),
      qos_(QosProfiles::Load(options.qos_file)),
      monitor_(std::make_unique<PeerMonitor>(options.name, options.domain_id)) {
  options_.ros_namespace = NormaliseNamespace(options.ros_namespace);
  if (options.domain_id < 0 || options.domain_id > kMaxDomainId) {
    throw config::ConfigError("domain id " + std::to_string(options.domain_id) + " is outside 0.." +
                              std::to_string(kMaxDomainId) + " (use 0.." +
                              std::to_string(kMaxSafeDomainId) + " on Linux)");
  }
  if (auto warning = DomainPortWarning(options.domain_id)) {
    std::cerr << options.name << ": WARNING: " << *warning << std::endl;
  }
#if !HAVE_SECURITY
  // Fast DDS built without security ignores the dds.sec properties: refuse
  // rather than run unprotected when protection was asked for.
  if (options.security.Enabled()) {
    throw config::ConfigError(
        "DDS Security was asked for (--security-keystore) but this Fast DDS was built without "
        "it (HAVE_SECURITY 0); install a Fast DDS with security or leave the option out");
  }
#endif
  auto participant_qos = qos_.Participant(options.participant_profile);
  participant_qos.name(options.name);
  // What Fast DDS resolved for the profile (from any file it loaded, e.g. a
  // DEFAULT_FASTRTPS_PROFILES.xml in the working folder), not only what
  // QosProfiles checked: the first property of a name wins, so none of the
  // profile's may stand before the enclave's.
  for (const auto& property : participant_qos.properties().properties()) {
    if (IsSecurityProperty(property.name())) {
      throw config::ConfigError(
          "participant profile '" + options.participant_profile + "' (" + options.qos_file +
          ") sets the DDS Security property '" + property.name() +
          "': structloc sets DDS Security from --security-keystore alone; remove the property");
    }
  }
  const auto security = SecurityProperties(options.security);
  for (const auto& [name, value] : security) {
    participant_qos.properties().properties().emplace_back(name, value);
  }
  {
    const std::lock_guard<std::mutex> lock(FastDdsProfileTables());
    participant_ =
        eprosima::fastdds::dds::DomainParticipantFactory::get_instance()->create_participant(
            options.domain_id, participant_qos, monitor_.get(),
            eprosima::fastdds::dds::StatusMask::none());
  }
  if (participant_ == nullptr && options.security.Enabled()) {
    throw std::runtime_error(
        "DDS Security refused the enclave " + options.security.EnclaveFolder() +
        ": a certificate, key, governance or permissions file there is invalid, expired, not "
        "signed by its CA or grants nothing on domain " +
        std::to_string(options.domain_id) + " (Fast DDS's log above says which)");
  }
  if (participant_ != nullptr) RequireSecurityAsAsked(security);
  if (participant_ == nullptr) {
    throw std::runtime_error("cannot create a DDS participant on domain " +
                             std::to_string(options.domain_id) + " with profile '" +
                             options.participant_profile + "' of " + options.qos_file);
  }
  publisher_ = participant_->create_publisher(eprosima::fastdds::dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(eprosima::fastdds::dds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    // The participant calls monitor_, which goes with this failed constructor.
    participant_->delete_contained_entities();
    eprosima::fastdds::dds::DomainParticipantFactory::get_instance()->delete_participant(
        participant_);
    throw std::runtime_error("cannot create publisher/subscriber");
  }
}

void Node::RequireSecurityAsAsked(
    const std::vector<std::pair<std::string, std::string>>& security) {
  // The participant's own view of its properties: each security property
  // must be the enclave's, and first of its name (the one Fast DDS uses).
  const auto& properties = participant_->get_qos().properties().properties();
  for (const auto& wanted : security) {
    const std::string& name = wanted.first;
    const auto first = std::find_if(properties.begin(), properties.end(),
                                    [&](const auto& property) { return property.name() == name; });
    if (first == properties.end() || first->value() != wanted.second) {
      participant_->delete_contained_entities();
      eprosima::fastdds::dds::DomainParticipantFactory::get_instance()->delete_participant(
          participant_);
      participant_ = nullptr;
      throw std::runtime_error("DDS Security: the participant was created with '" + name +
                               "' other than the enclave's; refusing to run unprotected");
    }
  }
}

void Node::ReleaseCallbacks() {
  callbacks_held_ = false;
  std::vector<std::weak_ptr<DetachableListener>> live;
  for (const auto& weak : listeners_) {
    if (auto listener = weak.lock()) {
      listener->TakeWaiting();
      live.push_back(weak);
    }
  }
  listeners_ = std::move(live);
}

Node::~Node() {
  if (participant_ != nullptr) {
    participant_->delete_contained_entities();
    eprosima::fastdds::dds::DomainParticipantFactory::get_instance()->delete_participant(
        participant_);
  }
}

std::string Node::Describe(const TopicSpec& topic, const std::string& type_name) {
  return topic.name + "  [" + type_name + "]  qos=" + topic.qos_profile;
}

std::string Node::EndpointReport() const {
  std::ostringstream out;
  out << options_.name << " on domain " << options_.domain_id << " (participant profile '"
      << options_.participant_profile << "' from " << options_.qos_file << ")\n";
  for (const auto& e : endpoints_) out << "  " << e << "\n";
  return out.str();
}

}  // namespace structloc::dds_common
