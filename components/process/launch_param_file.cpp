// ROS 2 parameter files (see header).
#include "structloc/process/launch_param_file.hpp"

#include <yaml-cpp/yaml.h>

#include <map>

#include "structloc/config/strict_xml.hpp"

namespace structloc::process {
namespace {

[[noreturn]] void Fail(const std::string& path, const YAML::Node& where, const std::string& what) {
  const auto mark = where.Mark();
  throw config::ConfigError(path + ":" + std::to_string(mark.line + 1) + ": " + what);
}

// A map key as text: a plain value (a list or map as a key is refused, as
// ROS 2 refuses it, instead of yaml-cpp's conversion error without the file).
std::string KeyText(const std::string& path, const YAML::Node& key, const char* what) {
  if (!key.IsScalar())
    Fail(path, key, std::string(what) + " must be a plain name, not a list or map");
  return key.Scalar();
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

// The parameters found so far, in the file's order, each name once (a later
// entry's value replaces an earlier one's).
class Parameters {
 public:
  void Set(const std::string& name, const std::string& value) {
    const auto [at, added] = index_.emplace(name, values_.size());
    if (added) {
      values_.emplace_back(name, value);
    } else {
      values_[at->second].second = value;
    }
  }
  std::vector<std::pair<std::string, std::string>> Take() { return std::move(values_); }

 private:
  std::vector<std::pair<std::string, std::string>> values_;
  std::map<std::string, size_t> index_;
};

// A map's keys, each once: YAML requires it, and yaml-cpp would keep both (a
// key repeated through an alias thousands of times also multiplied the work).
void RequireUniqueKeys(const std::string& path, const YAML::Node& map, const char* what) {
  std::map<std::string, int> lines;
  for (const auto& item : map) {
    const std::string key = KeyText(path, item.first, what);
    const auto [at, added] = lines.emplace(key, item.first.Mark().line + 1);
    if (!added) {
      Fail(path, item.first,
           std::string(what) + " '" + key + "' appears a second time (first on line " +
               std::to_string(at->second) + ")");
    }
  }
}

void AddEntry(const std::string& path, const YAML::Node& entry, Parameters& out) {
  if (!entry.IsMap() || entry.size() != 1 || !entry["ros__parameters"]) {
    Fail(path, entry, "a node's entry must hold exactly one map, ros__parameters");
  }
  const YAML::Node parameters = entry["ros__parameters"];
  if (!parameters.IsMap()) Fail(path, parameters, "ros__parameters must be a map of values");
  RequireUniqueKeys(path, parameters, "a parameter name");
  for (const auto& item : parameters) {
    const std::string key = item.first.Scalar();
    if (!item.second.IsScalar()) {
      Fail(path, item.second, "parameter '" + key + "' must be a plain value, not a list or map");
    }
    out.Set(key, item.second.Scalar());
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
  RequireUniqueKeys(path, root, "a node entry");
  Parameters out;
  for (const bool wildcard : {true, false}) {  // "/**" first: a node's own entry wins
    for (const auto& entry : root) {
      const std::string key = entry.first.Scalar();
      if ((key == "/**") == wildcard && Matches(key, qualified_name)) {
        AddEntry(path, entry.second, out);
      }
    }
  }
  return out.Take();
}

}  // namespace structloc::process
