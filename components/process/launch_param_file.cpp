// ROS 2 parameter files (see header).
#include "structloc/process/launch_param_file.hpp"

#include <yaml-cpp/yaml.h>

#include "structloc/config/strict_xml.hpp"

namespace structloc::process {
namespace {

[[noreturn]] void Fail(const std::string& path, const YAML::Node& where, const std::string& what) {
  const auto mark = where.Mark();
  throw config::ConfigError(path + ":" + std::to_string(mark.line + 1) + ": " + what);
}

// Whether an entry's key names the node ("/**", its name, or ns/name).
bool Matches(std::string key, const std::string& qualified_name) {
  if (key == "/**") return true;
  if (!key.empty() && key.front() == '/') key.erase(0, 1);
  const size_t slash = qualified_name.rfind('/');
  const std::string name =
      slash == std::string::npos ? qualified_name : qualified_name.substr(slash + 1);
  return key == qualified_name || key == name;
}

void AddEntry(const std::string& path, const YAML::Node& entry,
              std::vector<std::pair<std::string, std::string>>& out) {
  if (!entry.IsMap() || entry.size() != 1 || !entry["ros__parameters"]) {
    Fail(path, entry, "a node's entry must hold exactly one map, ros__parameters");
  }
  const YAML::Node parameters = entry["ros__parameters"];
  if (!parameters.IsMap()) Fail(path, parameters, "ros__parameters must be a map of values");
  for (const auto& item : parameters) {
    if (!item.second.IsScalar()) {
      Fail(path, item.second,
           "parameter '" + item.first.as<std::string>() +
               "' must be a plain value, not a list or map");
    }
    const std::string key = item.first.as<std::string>();
    bool replaced = false;
    for (auto& [name, value] : out) {
      if (name == key) {
        value = item.second.as<std::string>();
        replaced = true;
      }
    }
    if (!replaced) out.emplace_back(key, item.second.as<std::string>());
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> ReadNodeParameters(
    const std::string& path, const std::string& qualified_name) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw config::ConfigError(path + ": cannot read the parameter file");
  } catch (const YAML::Exception& e) {
    throw config::ConfigError(path + ":" + std::to_string(e.mark.line + 1) +
                              ": malformed YAML: " + e.msg);
  }
  if (!root.IsMap()) {
    throw config::ConfigError(path + ": a parameter file is a map of node entries");
  }
  std::vector<std::pair<std::string, std::string>> out;
  for (const bool wildcard : {true, false}) {  // "/**" first: a node's own entry wins
    for (const auto& entry : root) {
      const std::string key = entry.first.as<std::string>();
      if ((key == "/**") == wildcard && Matches(key, qualified_name)) {
        AddEntry(path, entry.second, out);
      }
    }
  }
  return out;
}

}  // namespace structloc::process
