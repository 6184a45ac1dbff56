// Launch XML reader (see header).
#include "launch_file.hpp"

#include <cstdlib>
#include <regex>
#include <set>

#include "strict_xml.hpp"

namespace structloc::process {
namespace {

using config::AttributeReader;
using config::XmlFile;

std::string Substitute(const XmlFile& file, const tinyxml2::XMLElement& where,
                       const std::string& text, const std::map<std::string, std::string>& vars,
                       const LaunchContext& context) {
  static const std::regex pattern(R"(\$\(([a-z-]+)(?: ([A-Za-z0-9_]+))?\))");
  std::string out;
  auto begin = std::sregex_iterator(text.begin(), text.end(), pattern);
  size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const auto& m = *it;
    out += text.substr(last, static_cast<size_t>(m.position()) - last);
    const std::string kind = m[1];
    const std::string name = m[2];
    if (kind == "var") {
      auto v = vars.find(name);
      if (v == vars.end()) file.Fail(where, "$(var " + name + ") names no <arg> declared above");
      out += v->second;
    } else if (kind == "find-pkg-share") {
      if (name != "structloc") file.Fail(where, "unknown package '" + name + "'");
      out += context.package_share_dir;
    } else if (kind == "env") {
      const char* value = std::getenv(name.c_str());
      if (value == nullptr) file.Fail(where, "environment variable " + name + " is not set");
      out += value;
    } else {
      file.Fail(where, "unknown substitution $(" + kind + ")");
    }
    last = static_cast<size_t>(m.position() + m.length());
  }
  out += text.substr(last);
  if (out.find("$(") != std::string::npos)
    file.Fail(where, "malformed substitution in '" + text + "'");
  return out;
}

}  // namespace

LaunchDescription ReadLaunchFile(const std::string& path, const LaunchContext& context) {
  const auto file = XmlFile::Load(path);
  const auto& root = file.Root("launch");
  config::RequireChildNames(file, root, {"arg", "node"});
  LaunchDescription description;
  std::set<std::string> used_overrides;
  std::set<std::string> node_names;
  for (const auto* e = root.FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    AttributeReader attrs(file, *e);
    if (std::string(e->Name()) == "arg") {
      const std::string name = attrs.String("name");
      auto fallback = attrs.OptionalString("default");
      attrs.OptionalString("description");
      attrs.Finish();
      auto override_it = context.overrides.find(name);
      if (override_it != context.overrides.end()) {
        description.arguments[name] = override_it->second;
        used_overrides.insert(name);
      } else if (fallback) {
        description.arguments[name] =
            Substitute(file, *e, *fallback, description.arguments, context);
      } else {
        file.Fail(*e, "argument '" + name + "' has no default; pass " + name + ":=VALUE");
      }
      continue;
    }
    NodeLaunch node;
    if (attrs.String("pkg") != "structloc") attrs.Fail("pkg must be \"structloc\"");
    const std::string exec = attrs.String("exec");
    if (exec.find('/') != std::string::npos) attrs.Fail("exec must be a plain executable name");
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
      node.arguments.push_back(Substitute(file, *p, value, description.arguments, context));
    }
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
