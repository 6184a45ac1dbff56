// Launch XML reader (see header).
#include "structloc/process/launch_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <regex>
#include <set>

#include "structloc/config/strict_xml.hpp"

namespace structloc::process {
namespace {

using config::AttributeReader;
using config::XmlFile;

// Builds one substituted value, refusing to grow it beyond the limits before
// any memory is spent on it.
class ValueBuilder {
 public:
  ValueBuilder(const XmlFile& file, const tinyxml2::XMLElement& where, const LaunchContext& context,
               size_t* total_bytes)
      : file_(file), where_(where), context_(context), total_bytes_(total_bytes) {}

  void Append(const std::string& piece) {
    if (piece.size() > context_.max_value_bytes - value_.size()) {
      file_.Fail(where_, "substituted value longer than " +
                             std::to_string(context_.max_value_bytes) +
                             " bytes (structloc launch --max-value-bytes)");
    }
    if (piece.size() > context_.max_total_bytes - *total_bytes_) {
      file_.Fail(where_, "substituted values of the file exceed " +
                             std::to_string(context_.max_total_bytes) +
                             " bytes in total (structloc launch --max-total-bytes)");
    }
    value_ += piece;
    *total_bytes_ += piece.size();
  }
  const std::string& Value() const { return value_; }

 private:
  const XmlFile& file_;
  const tinyxml2::XMLElement& where_;
  const LaunchContext& context_;
  size_t* total_bytes_;
  std::string value_;
};

std::string Substitute(const XmlFile& file, const tinyxml2::XMLElement& where,
                       const std::string& text, const std::map<std::string, std::string>& vars,
                       const LaunchContext& context, size_t* total_bytes) {
  // std::regex recurses per character: refuse over-long text before matching.
  if (text.size() > context.max_value_bytes) {
    file.Fail(where, "attribute text longer than " + std::to_string(context.max_value_bytes) +
                         " bytes (--max-value-bytes)");
  }
  static const std::regex pattern(R"(\$\(([a-z-]+)(?: ([A-Za-z0-9_]+))?\))");
  ValueBuilder out(file, where, context, total_bytes);
  auto begin = std::sregex_iterator(text.begin(), text.end(), pattern);
  size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const auto& m = *it;
    out.Append(text.substr(last, static_cast<size_t>(m.position()) - last));
    const std::string kind = m[1];
    const std::string name = m[2];
    if (kind == "var") {
      auto v = vars.find(name);
      if (v == vars.end()) file.Fail(where, "$(var " + name + ") names no <arg> declared above");
      out.Append(v->second);
    } else if (kind == "find-pkg-share") {
      if (name != "structloc") file.Fail(where, "unknown package '" + name + "'");
      out.Append(context.package_share_dir);
    } else if (kind == "env") {
      const char* value = std::getenv(name.c_str());
      if (value == nullptr) file.Fail(where, "environment variable " + name + " is not set");
      out.Append(value);
    } else {
      file.Fail(where, "unknown substitution $(" + kind + ")");
    }
    last = static_cast<size_t>(m.position() + m.length());
  }
  out.Append(text.substr(last));
  if (out.Value().find("$(") != std::string::npos)
    file.Fail(where, "malformed substitution in '" + text + "'");
  return out.Value();
}

// The node's executable must be a runnable file in the executables folder.
void RequireExecutable(const XmlFile& file, const tinyxml2::XMLElement& node,
                       const std::string& exec, const std::string& path) {
  struct stat info {};
  if (stat(path.c_str(), &info) != 0) {
    file.Fail(node, "exec '" + exec + "': " + path + ": " + std::strerror(errno));
  }
  if (S_ISDIR(info.st_mode)) file.Fail(node, "exec '" + exec + "': " + path + " is a folder");
  if (!S_ISREG(info.st_mode) || access(path.c_str(), X_OK) != 0) {
    file.Fail(node, "exec '" + exec + "': " + path + " is not an executable file");
  }
}

}  // namespace

LaunchDescription ReadLaunchFile(const std::string& path, const LaunchContext& context) {
  const auto file = XmlFile::Load(path);
  const auto& root = file.Root("launch");
  config::RequireChildNames(file, root, {"arg", "node"});
  LaunchDescription description;
  size_t total_bytes = 0;
  std::set<std::string> used_overrides;
  std::set<std::string> node_names;
  for (const auto* e = root.FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    AttributeReader attrs(file, *e);
    if (std::string(e->Name()) == "arg") {
      const std::string name = attrs.String("name");
      auto fallback = attrs.OptionalString("default");
      attrs.OptionalString("description");
      attrs.Finish();
      if (description.arguments.count(name) != 0) {
        file.Fail(*e, "a second <arg name=\"" + name + "\">; each argument is declared once");
      }
      auto override_it = context.overrides.find(name);
      if (override_it != context.overrides.end()) {
        description.arguments[name] = override_it->second;
        used_overrides.insert(name);
      } else if (fallback) {
        description.arguments[name] =
            Substitute(file, *e, *fallback, description.arguments, context, &total_bytes);
      } else {
        file.Fail(*e, "argument '" + name + "' has no default; pass " + name + ":=VALUE");
      }
      continue;
    }
    NodeLaunch node;
    if (attrs.String("pkg") != "structloc") attrs.Fail("pkg must be \"structloc\"");
    const std::string exec = attrs.String("exec");
    if (exec.find('/') != std::string::npos || exec.empty() || exec == "." || exec == "..") {
      attrs.Fail("exec must be a plain executable name, not '" + exec + "'");
    }
    node.executable = context.executables_dir + "/" + exec;
    node.name = attrs.OptionalString("name").value_or(exec);
    attrs.OptionalString("output");
    attrs.Finish();
    if (!node_names.insert(node.name).second)
      file.Fail(*e, "duplicate node name '" + node.name + "'");
    config::RequireChildNames(file, *e, {"param"});
    for (const auto* p = e->FirstChildElement(); p != nullptr; p = p->NextSiblingElement()) {
      AttributeReader param(file, *p);
      const std::string name = param.String("name");
      const std::string value = param.String("value");
      param.Finish();
      node.arguments.push_back("--" + name);
      node.arguments.push_back(
          Substitute(file, *p, value, description.arguments, context, &total_bytes));
    }
    RequireExecutable(file, *e, exec, node.executable);
    description.nodes.push_back(std::move(node));
  }
  for (const auto& [name, value] : context.overrides) {
    if (used_overrides.count(name) == 0) {
      throw config::ConfigError(path + ": no <arg name=\"" + name + "\"> to take " + name +
                                ":=" + value);
    }
  }
  if (description.nodes.empty()) throw config::ConfigError(path + ": launches no <node>");
  return description;
}

}  // namespace structloc::process
