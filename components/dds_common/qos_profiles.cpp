// QoS profile validation and lookup (see qos_profiles.hpp).
#include "structloc/dds_common/qos_profiles.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include <cctype>
#include <map>
#include <mutex>
#include <string_view>

#include "structloc/config/strict_number.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/dds_common/topics.hpp"

namespace structloc::dds_common {
namespace {

using eprosima::fastrtps::types::ReturnCode_t;

constexpr long kMaxDepth = 100000;

const std::map<std::string, std::set<std::string>>& KnownKinds() {
  static const std::map<std::string, std::set<std::string>> kinds = {
      {"reliability", {"BEST_EFFORT", "RELIABLE"}},
      {"durability", {"VOLATILE", "TRANSIENT_LOCAL", "TRANSIENT", "PERSISTENT"}},
      {"historyQos", {"KEEP_LAST", "KEEP_ALL"}},
      {"liveliness", {"AUTOMATIC", "MANUAL_BY_PARTICIPANT", "MANUAL_BY_TOPIC"}},
      {"ownership", {"SHARED", "EXCLUSIVE"}},
      {"destinationOrder", {"BY_RECEPTION_TIMESTAMP", "BY_SOURCE_TIMESTAMP"}},
      {"publishMode", {"SYNCHRONOUS", "ASYNCHRONOUS"}},
      {"data_sharing", {"AUTOMATIC", "ON", "OFF"}},
  };
  return kinds;
}

bool IsNonNegativeInteger(const char* text, long max, long* out) {
  if (text == nullptr) return false;
  const auto value = config::ParseInteger(text);
  if (!value || *value < 0 || *value > max) return false;
  *out = static_cast<long>(*value);
  return true;
}

// Walks one profile element and rejects values Fast DDS would accept silently.
void CheckValues(const config::XmlFile& file, const tinyxml2::XMLElement& element) {
  for (const auto* child = element.FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    const std::string name = child->Name();
    const char* text = child->GetText();
    long value = 0;
    if (name == "depth") {
      if (!IsNonNegativeInteger(text, kMaxDepth, &value) || value < 1) {
        file.Fail(*child, "history depth '" + std::string(text ? text : "") +
                              "' must be an integer from 1 to " + std::to_string(kMaxDepth));
      }
    } else if (name == "sec" || name == "nanosec") {
      const std::string t = text ? text : "";
      const bool infinite =
          t == "DURATION_INFINITY" || t == "DURATION_INFINITE_SEC" || t == "DURATION_INFINITE_NSEC";
      if (!infinite && !IsNonNegativeInteger(text, 2147483647L, &value)) {
        file.Fail(*child, "duration '" + t + "' must be a non-negative integer");
      }
    } else if (name == "kind") {
      const auto& kinds = KnownKinds();
      auto it = kinds.find(element.Name());
      const std::string t = text ? text : "";
      if (it != kinds.end() && it->second.count(t) == 0) {
        file.Fail(*child, "unknown " + std::string(element.Name()) + " kind '" + t + "'");
      }
    }
    CheckValues(file, *child);
  }
}

// A <leaseDuration> of zero makes Fast DDS fail when the participant is
// created, with only its own log line; refuse it here with file:line.
void CheckLease(const config::XmlFile& file, const tinyxml2::XMLElement& lease) {
  bool zero = true;
  for (const char* part : {"sec", "nanosec"}) {
    const auto* e = lease.FirstChildElement(part);
    const char* text = e != nullptr ? e->GetText() : nullptr;
    if (text != nullptr && std::string(text) != "0") zero = false;
  }
  if (zero) file.Fail(lease, "leaseDuration must be longer than 0 (structloc ships 3 s)");
}

void CheckLeases(const config::XmlFile& file, const tinyxml2::XMLElement& element) {
  for (const auto* child = element.FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    if (std::string(child->Name()) == "leaseDuration") CheckLease(file, *child);
    CheckLeases(file, *child);
  }
}

// Every profile the components create endpoints with (topics.hpp).
std::set<std::string> TopicProfiles() {
  std::set<std::string> names;
  for (const auto* topic :
       {&topics::kScan, &topics::kOdom, &topics::kWheelEncoders, &topics::kGroundTruth,
        &topics::kCmdVel, &topics::kPose, &topics::kInitialPose, &topics::kTf, &topics::kFeatures,
        &topics::kStatus, &topics::kCalibration, &topics::kDiagnostics}) {
    names.insert(topic->qos_profile);
  }
  return names;
}

// DDS Security is set up from an enclave (--security-keystore) alone: a
// profile's own dds.sec.* property would come first in the participant's
// properties, and Fast DDS takes the first of a name, so one naming another
// authentication plugin (or none) would switch security off, or point it at
// files that were never checked. Refused wherever it appears in the file.
void RefuseSecurityProperties(const config::XmlFile& file, const tinyxml2::XMLElement& element) {
  for (const auto* child = element.FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    if (std::string(child->Name()) == "property") {
      const auto* name = child->FirstChildElement("name");
      const char* text = name != nullptr ? name->GetText() : nullptr;
      if (text != nullptr && IsSecurityProperty(text)) {
        file.Fail(*child, "property '" + std::string(text) +
                              "' configures DDS Security: structloc sets DDS Security from "
                              "--security-keystore alone (an enclave made by structloc_keystore); "
                              "remove the property");
      }
    }
    RefuseSecurityProperties(file, *child);
  }
}

std::string ProfileName(const config::XmlFile& file, const tinyxml2::XMLElement& element) {
  const char* name = element.Attribute("profile_name");
  if (name == nullptr || *name == '\0') file.Fail(element, "profile without profile_name");
  return name;
}

}  // namespace

std::mutex& FastDdsProfileTables() {
  static std::mutex tables;
  return tables;
}

bool IsSecurityProperty(const std::string& name) {
  const auto first = name.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return false;
  constexpr std::string_view kPrefix = "dds.sec.";
  if (name.size() - first < kPrefix.size()) return false;
  for (size_t i = 0; i < kPrefix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(name[first + i])) != kPrefix[i]) return false;
  }
  return true;
}

QosProfiles QosProfiles::Load(const std::string& path) {
  QosProfiles result = Check(path);
  auto* factory = eprosima::fastdds::dds::DomainParticipantFactory::get_instance();
  const std::lock_guard<std::mutex> lock(FastDdsProfileTables());
  if (factory->load_XML_profiles_file(path) != ReturnCode_t::RETCODE_OK) {
    throw QosError("QoS profiles: " + path +
                   ": Fast DDS rejected the file (see its log above for the element)");
  }
  return result;
}

QosProfiles QosProfiles::Check(const std::string& path) {
  QosProfiles result;
  result.path_ = path;
  try {
    const auto file = config::XmlFile::Load(path);
    const auto& root = file.Root();
    const tinyxml2::XMLElement* profiles =
        std::string(root.Name()) == "profiles" ? &root : root.FirstChildElement("profiles");
    if (std::string(root.Name()) != "dds" && profiles != &root) {
      file.Fail(root, "root element must be <dds> or <profiles>");
    }
    if (profiles == nullptr) file.Fail(root, "no <profiles> element");
    RefuseSecurityProperties(file, root);
    for (const auto* e = profiles->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      const std::string kind = e->Name();
      std::set<std::string>* names = nullptr;
      if (kind == "participant") names = &result.participant_profiles_;
      if (kind == "data_writer" || kind == "publisher") names = &result.writer_profiles_;
      if (kind == "data_reader" || kind == "subscriber") names = &result.reader_profiles_;
      if (names == nullptr) continue;
      const std::string name = ProfileName(file, *e);
      if (!names->insert(name).second) file.Fail(*e, "duplicate profile '" + name + "'");
      CheckValues(file, *e);
      CheckLeases(file, *e);
    }
  } catch (const config::ConfigError& e) {
    throw QosError(std::string("QoS profiles: ") + e.what());
  }
  if (result.participant_profiles_.empty()) {
    throw QosError("QoS profiles: " + path + ": defines no <participant> profile");
  }
  for (const auto& profile : TopicProfiles()) {
    for (const auto& [kind, names] : {std::pair{"data_writer", &result.writer_profiles_},
                                      std::pair{"data_reader", &result.reader_profiles_}}) {
      if (names->count(profile) == 0) {
        throw QosError("QoS profiles: " + path + ": no <" + kind + " profile_name=\"" + profile +
                       "\">, which the components' topics use");
      }
    }
  }
  return result;
}

eprosima::fastdds::dds::DomainParticipantQos QosProfiles::Participant(
    const std::string& profile) const {
  eprosima::fastdds::dds::DomainParticipantQos qos;
  const std::lock_guard<std::mutex> lock(FastDdsProfileTables());
  if (participant_profiles_.count(profile) == 0 ||
      eprosima::fastdds::dds::DomainParticipantFactory::get_instance()
              ->get_participant_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw QosError("QoS profiles: " + path_ + ": no participant profile '" + profile + "'");
  }
  return qos;
}

namespace {
// A writer or reader QoS from a validated profile, with the depth re-checked
// on what Fast DDS actually parsed.
template <class Qos, class Entity, class Lookup>
Qos EndpointQos(const std::string& path, const std::set<std::string>& known, Entity& entity,
                const std::string& profile, const char* kind, Lookup lookup) {
  Qos qos;
  std::unique_lock<std::mutex> lock(FastDdsProfileTables());
  if (known.count(profile) == 0 || (entity.*lookup)(profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw QosError("QoS profiles: " + path + ": no " + kind + " profile '" + profile + "'");
  }
  lock.unlock();
  if (qos.history().kind == eprosima::fastdds::dds::KEEP_LAST_HISTORY_QOS &&
      qos.history().depth < 1) {
    throw QosError("QoS profiles: " + path + ": " + kind + " '" + profile + "' has depth < 1");
  }
  return qos;
}
}  // namespace

eprosima::fastdds::dds::DataWriterQos QosProfiles::Writer(
    eprosima::fastdds::dds::Publisher& publisher, const std::string& profile) const {
  return EndpointQos<eprosima::fastdds::dds::DataWriterQos>(
      path_, writer_profiles_, publisher, profile, "data_writer",
      &eprosima::fastdds::dds::Publisher::get_datawriter_qos_from_profile);
}

eprosima::fastdds::dds::DataReaderQos QosProfiles::Reader(
    eprosima::fastdds::dds::Subscriber& subscriber, const std::string& profile) const {
  return EndpointQos<eprosima::fastdds::dds::DataReaderQos>(
      path_, reader_profiles_, subscriber, profile, "data_reader",
      &eprosima::fastdds::dds::Subscriber::get_datareader_qos_from_profile);
}

}  // namespace structloc::dds_common
