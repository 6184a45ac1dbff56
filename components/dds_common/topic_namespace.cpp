// ROS 2 namespaces for topics (see header).
#include "structloc/dds_common/topic_namespace.hpp"

#include <cctype>

#include "structloc/config/strict_xml.hpp"

namespace structloc::dds_common {

std::string NormaliseNamespace(const std::string& ns) {
  const size_t first = ns.find_first_not_of('/');
  if (first == std::string::npos) return "";
  const std::string inner = ns.substr(first, ns.find_last_not_of('/') - first + 1);
  size_t start = 0;
  while (true) {
    const size_t slash = inner.find('/', start);
    const std::string token =
        inner.substr(start, slash == std::string::npos ? slash : slash - start);
    bool valid =
        !token.empty() && (std::isalpha(static_cast<unsigned char>(token[0])) || token[0] == '_');
    for (const char c : token) {
      valid = valid && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
    }
    if (!valid) {
      throw config::ConfigError("--namespace '" + ns +
                                "' is not a ROS 2 namespace: each '/'-separated part must start "
                                "with a letter or '_' and hold only letters, digits and '_' "
                                "(e.g. robot1 or fleet/robot1)");
    }
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return inner;
}

TopicSpec InNamespace(const TopicSpec& topic, const std::string& ns) {
  const std::string prefix = "rt/";
  if (ns.empty() || topic.name.compare(0, prefix.size(), prefix) != 0) return topic;
  return {prefix + ns + "/" + topic.name.substr(prefix.size()), topic.qos_profile};
}

}  // namespace structloc::dds_common
