// Launch XML reader (see header).
#include "structloc/process/launch_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>

#include "structloc/config/strict_xml.hpp"
#include "structloc/process/launch_param_file.hpp"

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

// One "$(KIND NAME)" of a text: KIND in [a-z-]+, NAME (optional) in
// [A-Za-z0-9_]+.
struct SubstitutionSpan {
  size_t begin = 0;  // at "$("
  size_t end = 0;    // just past ")"
  std::string kind;
  std::string name;
};

// The substitution that starts at text[at] == '$', '(' or nullopt when what
// follows is no well-formed substitution. Read by hand in one pass, with no
// recursion: a recursive matcher (libstdc++'s std::regex) needs stack in
// proportion to the text and overflows it on an attribute of 30 000 bytes.
std::optional<SubstitutionSpan> ReadSubstitution(const std::string& text, size_t at) {
  const auto run = [&](size_t from, auto accepts) {
    size_t to = from;
    while (to < text.size() && accepts(static_cast<unsigned char>(text[to]))) ++to;
    return to;
  };
  SubstitutionSpan span;
  span.begin = at;
  const size_t kind_end = run(at + 2, [](unsigned char c) { return std::islower(c) || c == '-'; });
  if (kind_end == at + 2) return std::nullopt;
  span.kind = text.substr(at + 2, kind_end - at - 2);
  size_t next = kind_end;
  if (next < text.size() && text[next] == ' ') {
    const size_t name_end =
        run(next + 1, [](unsigned char c) { return std::isalnum(c) || c == '_'; });
    if (name_end == next + 1) return std::nullopt;
    span.name = text.substr(next + 1, name_end - next - 1);
    next = name_end;
  }
  if (next >= text.size() || text[next] != ')') return std::nullopt;
  span.end = next + 1;
  return span;
}

// A text for an error message: at most 80 characters of it.
std::string Excerpt(const std::string& text) {
  constexpr size_t kShown = 80;
  return text.size() <= kShown
             ? text
             : text.substr(0, kShown) + "... (" + std::to_string(text.size()) + " characters)";
}

// `environment`: the <set_env>s in scope, which $(env NAME) sees before the
// launcher's own environment (as the nodes will).
std::string Substitute(const XmlFile& file, const tinyxml2::XMLElement& where,
                       const std::string& text, const std::map<std::string, std::string>& vars,
                       const std::vector<std::pair<std::string, std::string>>& environment,
                       const LaunchContext& context, size_t* total_bytes) {
  if (text.size() > context.max_value_bytes) {
    file.Fail(where, "attribute text longer than " + std::to_string(context.max_value_bytes) +
                         " bytes (--max-value-bytes)");
  }
  ValueBuilder out(file, where, context, total_bytes);
  size_t last = 0;
  // Every "$(" of the text itself must start a substitution (a value
  // substituted into it may hold one: a folder may be called "a$(b").
  for (size_t at = text.find("$("); at != std::string::npos; at = text.find("$(", last)) {
    const auto m = ReadSubstitution(text, at);
    if (!m) file.Fail(where, "malformed substitution in '" + Excerpt(text) + "'");
    out.Append(text.substr(last, at - last));
    const std::string& kind = m->kind;
    const std::string& name = m->name;
    if (kind == "var") {
      auto v = vars.find(name);
      if (v == vars.end()) {
        file.Fail(where, "$(var " + name + ") names no <arg> or <let> set above");
      }
      out.Append(v->second);
    } else if (kind == "dirname") {
      if (!name.empty()) file.Fail(where, "$(dirname) takes no argument");
      // As ROS 2's: the folder of the launch file being read (of the included
      // file inside it), so that files beside it are found from anywhere.
      out.Append(std::filesystem::absolute(file.Path()).parent_path().string());
    } else if (kind == "find-pkg-share") {
      if (name != "structloc") file.Fail(where, "unknown package '" + name + "'");
      out.Append(context.package_share_dir);
    } else if (kind == "env") {
      const auto set = std::find_if(environment.begin(), environment.end(),
                                    [&](const auto& variable) { return variable.first == name; });
      const char* value =
          set != environment.end() ? set->second.c_str() : std::getenv(name.c_str());
      if (value == nullptr) file.Fail(where, "environment variable " + name + " is not set");
      out.Append(value);
    } else {
      file.Fail(where, "unknown substitution $(" + kind + ")");
    }
    last = m->end;
  }
  out.Append(text.substr(last));
  return out.Value();
}

// Letters, digits and '_', not starting with a digit: an environment
// variable's name, and a ROS 2 node's.
bool IsPlainName(const std::string& name) {
  bool valid = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0]));
  for (const char c : name) {
    valid = valid && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  }
  return valid;
}

// A command's words as ROS 2 splits them: at white space of the text itself,
// never inside a substitution "$(...)" (whose value stays one word after
// substitution, spaces and all: a folder called "my maps").
std::vector<std::string> CommandWords(const std::string& cmd) {
  std::vector<std::string> words;
  std::string word;
  int depth = 0;
  for (size_t i = 0; i < cmd.size(); ++i) {
    const char c = cmd[i];
    if (c == '$' && i + 1 < cmd.size() && cmd[i + 1] == '(') ++depth;
    if (c == ')' && depth > 0) --depth;
    if (depth == 0 && std::isspace(static_cast<unsigned char>(c))) {
      if (!word.empty()) words.push_back(word);
      word.clear();
    } else {
      word += c;
    }
  }
  if (!word.empty()) words.push_back(word);
  return words;
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

// Counts the file at `path` against the reading bounds before it is read
// (its size from the file system; a missing file counts as one of no bytes):
// a refusal names the element that reads it (`where` in `file`) and the
// option that sets the bound.
void CountFileRead(const XmlFile* file, const tinyxml2::XMLElement* where, const std::string& path,
                   const LaunchContext& context, size_t* files_read, size_t* read_bytes) {
  const auto fail = [&](const std::string& what) {
    if (file != nullptr && where != nullptr) file->Fail(*where, what);
    throw config::ConfigError(path + ": " + what);
  };
  if (++*files_read > context.max_files_read) {
    fail("reading " + path + " makes more than " + std::to_string(context.max_files_read) +
         " launch and parameter files read in all, each include counted every time it is read "
         "(structloc launch --max-files)");
  }
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  const size_t bytes = error ? 0 : static_cast<size_t>(size);
  if (bytes > context.max_read_bytes - std::min(*read_bytes, context.max_read_bytes)) {
    fail("reading " + path + " (" + std::to_string(bytes) + " bytes) makes more than " +
         std::to_string(context.max_read_bytes) +
         " bytes of launch and parameter files read in all (structloc launch --max-read-bytes)");
  }
  *read_bytes += bytes;
}

// What a <group> scopes: the variables (<arg>s, <let>s, an <include>'s
// <arg>s and NAME:=VALUE from the command line) and the ROS 2 namespace pushed
// so far. An <include> is not scoped (as in ROS 2: a file is included as if
// written in its place), so what an included file sets stays set after it.
struct Scope {
  std::map<std::string, std::string> vars;
  std::string ros_namespace;
  std::vector<std::pair<std::string, std::string>> environment;  // <set_env>s, in order
};

// Sets `name` to `value` in `environment`, replacing an earlier value.
void SetVariable(std::vector<std::pair<std::string, std::string>>& environment,
                 const std::string& name, const std::string& value) {
  for (auto& [key, old] : environment) {
    if (key == name) {
      old = value;
      return;
    }
  }
  environment.emplace_back(name, value);
}

// The state of one file's reading.
class LaunchReader {
 public:
  // `read_bytes`: the size of `file`, already counted against the bounds.
  LaunchReader(const XmlFile& file, const LaunchContext& context, size_t read_bytes)
      : file_(file), context_(context), shared_(&own_shared_) {
    own_shared_.read_bytes = read_bytes;
  }

  // The file as included by `includer`, which passes it the arguments named
  // `passed` (already set in the scope it reads in).
  LaunchReader(const XmlFile& file, const LaunchReader& includer,
               const std::set<std::string>& passed)
      : file_(file),
        context_(includer.context_),
        includers_(includer.includers_),
        passed_(&passed),
        shared_(includer.shared_) {
    includers_.push_back(includer.file_.Path());
  }

  // The launch file named on the command line: its variables start as the
  // command line's NAME:=VALUEs, which any file's <arg> may take.
  LaunchDescription Read() {
    Scope scope;
    scope.vars = context_.overrides;
    Walk(file_.Root("launch"), scope, true);
    for (const auto& [name, value] : context_.overrides) {
      if (shared_->declared.count(name) == 0) {
        throw config::ConfigError(file_.Path() + ": no <arg name=\"" + name + "\"> to take " +
                                  name + ":=" + value);
      }
    }
    if (description_.nodes.empty()) {
      throw config::ConfigError(file_.Path() + ": launches no <node> or <executable>");
    }
    return std::move(description_);
  }

  // An included file, read in its includer's scope (and changing it, as in
  // ROS 2); it may launch nothing where its conditions say so.
  LaunchDescription ReadIncluded(Scope& scope) {
    Walk(file_.Root("launch"), scope, true);
    return std::move(description_);
  }

 private:
  // The children of <launch> (top) or of a <group>, in order.
  void Walk(const tinyxml2::XMLElement& parent, Scope& scope, bool top) {
    if (top) {
      config::RequireChildNames(
          file_, parent, {"arg", "let", "set_env", "node", "executable", "group", "include"});
    } else {
      config::RequireChildNames(
          file_, parent,
          {"let", "set_env", "node", "executable", "group", "include", "push-ros-namespace"});
    }
    for (const auto* e = parent.FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      if (tag == "arg") {
        Argument(*e, scope);
      } else if (tag == "let") {
        AttributeReader attrs(file_, *e);
        const std::string name = attrs.String("name");
        const std::string value = attrs.String("value");
        attrs.Finish();
        scope.vars[name] = Substitute(*e, value, scope);
      } else if (tag == "set_env") {
        const auto [name, value] = Variable(*e, scope);
        SetVariable(scope.environment, name, value);
      } else if (tag == "push-ros-namespace") {
        AttributeReader attrs(file_, *e);
        const std::string pushed = attrs.String("namespace");
        attrs.Finish();
        scope.ros_namespace = Join(scope.ros_namespace, Substitute(*e, pushed, scope));
      } else if (tag == "include") {
        Include(*e, scope);
      } else if (tag == "group") {
        AttributeReader attrs(file_, *e);
        const bool active = Condition(*e, attrs, scope);
        attrs.Finish();
        Scope inner = scope;  // what the group sets stays in it
        if (active) {
          Walk(*e, inner, false);
        } else {
          NoteArgumentsLeftOut(*e, scope);
        }
      } else if (tag == "executable") {
        Executable(*e, scope);
      } else {
        Node(*e, scope);
      }
    }
  }

  // <include file="F"> with <arg name value/> children: F is read as if
  // written here (ROS 2's <include> is not scoped: F sees the variables set
  // so far, and what F sets stays set after it; a <group> around the
  // <include> scopes it). The given values are set first, so F's <arg>s take
  // them. An argument without a default that the <include> does not pass is
  // an error (ROS 2's check), and so is one F does not declare (ROS 2 would
  // set it silently: a misspelt name would be lost).
  void Include(const tinyxml2::XMLElement& e, Scope& scope) {
    constexpr size_t kMaxDepth = 8;
    AttributeReader attrs(file_, e);
    const std::string file_text = attrs.String("file");
    // The condition first: an include left out may name a file that only
    // exists, or a variable only set, where it is wanted.
    const bool active = Condition(e, attrs, scope);
    attrs.Finish();
    config::RequireChildNames(file_, e, {"arg"});
    if (!active) {
      NoteArgumentsLeftOut(e, scope);
      return;
    }
    const std::string path = Substitute(e, file_text, scope);
    std::vector<std::string> chain = includers_;
    chain.push_back(file_.Path());
    for (const auto& f : chain) {
      if (f == path || chain.size() > kMaxDepth) {
        file_.Fail(e, "includes " + path + (f == path ? ", which includes itself" : "") +
                          " (includes nest at most " + std::to_string(kMaxDepth) + " deep)");
      }
    }
    // Set one after the other, as ROS 2 does: a value may name one set above it.
    std::set<std::string> passed;
    for (const auto* a = e.FirstChildElement(); a != nullptr; a = a->NextSiblingElement()) {
      AttributeReader arg(file_, *a);
      const std::string name = arg.String("name");
      const std::string value = arg.String("value");
      arg.Finish();
      scope.vars[name] = Substitute(*a, value, scope);
      passed.insert(name);
    }
    LaunchDescription description;
    CountRead(e, path);
    try {
      const auto included = XmlFile::Load(path);
      description = LaunchReader(included, *this, passed).ReadIncluded(scope);
      for (const auto& name : passed) {
        if (description.arguments.count(name) == 0) {
          throw config::ConfigError(path + ": no <arg name=\"" + name + "\"> to take the value " +
                                    "the <include> gives it");
        }
      }
    } catch (const config::ConfigError& error) {
      file_.Fail(e, std::string("in the included file: ") + error.what());  // both places named
    }
    for (auto& node : description.nodes) {
      if (!node_names_.insert(node.name).second) {
        file_.Fail(e, "duplicate node name '" + node.name + "' (from " + path + ")");
      }
      description_.nodes.push_back(std::move(node));
    }
  }

  // The <arg>s of the files that `e` (an <include> or <group> left out by its
  // condition) would include, as far as their names can be substituted now:
  // NAME:=VALUE for one of them is not refused as unknown (ROS 2 collects
  // such arguments as "conditionally included"). Nothing else is read.
  void NoteArgumentsLeftOut(const tinyxml2::XMLElement& e, const Scope& scope) {
    if (std::string(e.Name()) == "group") {
      for (const auto* c = e.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
        if (std::string(c->Name()) == "include" || std::string(c->Name()) == "group") {
          NoteArgumentsLeftOut(*c, scope);
        }
      }
      return;
    }
    const char* file = e.Attribute("file");
    if (file == nullptr) return;
    std::string path;
    try {
      path = Substitute(e, file, scope);
    } catch (const config::ConfigError&) {
      return;  // a variable only set where the include is wanted
    }
    CountRead(e, path);
    try {
      const auto included = XmlFile::Load(path);
      const auto& root = included.Root("launch");
      for (const auto* a = root.FirstChildElement("arg"); a != nullptr;
           a = a->NextSiblingElement("arg")) {
        if (const char* name = a->Attribute("name")) shared_->declared.insert(name);
      }
    } catch (const config::ConfigError&) {
      // A file or variable that only exists where the include is wanted.
    }
  }

  // <arg name="N" default="D"/>: as ROS 2 declares a launch argument, N keeps
  // a value already set (NAME:=VALUE on the command line, an <include>'s
  // <arg>, or a variable of the including file), else takes the default.
  void Argument(const tinyxml2::XMLElement& e, Scope& scope) {
    AttributeReader attrs(file_, e);
    const std::string name = attrs.String("name");
    auto fallback = attrs.OptionalString("default");
    attrs.OptionalString("description");
    attrs.Finish();
    if (description_.arguments.count(name) != 0) {
      file_.Fail(e, "a second <arg name=\"" + name + "\">; each argument is declared once");
    }
    shared_->declared.insert(name);
    if (!fallback && passed_ != nullptr && passed_->count(name) == 0) {
      file_.Fail(e, "argument '" + name + "' has no default; the <include> must pass it");
    }
    auto set = scope.vars.find(name);
    std::string value;
    if (set != scope.vars.end()) {
      value = set->second;
    } else if (fallback) {
      value = Substitute(e, *fallback, scope);
    } else {
      file_.Fail(e, "argument '" + name + "' has no default; pass " + name + ":=VALUE");
    }
    description_.arguments[name] = value;
    scope.vars[name] = value;
  }

  void Node(const tinyxml2::XMLElement& e, const Scope& scope) {
    AttributeReader attrs(file_, e);
    NodeLaunch node;
    if (attrs.String("pkg") != "structloc") attrs.Fail("pkg must be \"structloc\"");
    const std::string exec = attrs.String("exec");
    if (exec.find('/') != std::string::npos || exec.empty() || exec == "." || exec == "..") {
      attrs.Fail("exec must be a plain executable name, not '" + exec + "'");
    }
    node.executable = context_.executables_dir + "/" + exec;
    const auto name = attrs.OptionalString("name");
    const auto pushed = attrs.OptionalString("namespace");
    if (!ProcessAttributes(e, attrs, scope, node)) return;
    node.name = name ? NodeName(e, *name, scope) : exec;
    const std::string ros_namespace =
        Join(scope.ros_namespace, Substitute(e, pushed.value_or(""), scope));
    if (!ros_namespace.empty()) node.name = ros_namespace + "/" + node.name;
    AddNodeName(e, node.name);
    config::RequireChildNames(file_, e, {"param", "env"});
    node.environment = scope.environment;
    if (!ros_namespace.empty()) {
      node.arguments.push_back("--namespace");
      node.arguments.push_back(ros_namespace);
    }
    for (const auto* p = e.FirstChildElement(); p != nullptr; p = p->NextSiblingElement()) {
      if (std::string(p->Name()) == "env") {
        const auto [name, value] = Variable(*p, scope);
        SetVariable(node.environment, name, value);
        continue;
      }
      if (p->Attribute("from") != nullptr) {
        AttributeReader param(file_, *p);
        const std::string from = Substitute(*p, param.String("from"), scope);
        param.Finish();
        CountRead(*p, from);
        try {
          for (const auto& [name, value] : ReadNodeParameters(from, node.name)) {
            node.arguments.push_back("--" + name);
            node.arguments.push_back(value);
          }
        } catch (const config::ConfigError& error) {
          file_.Fail(*p, std::string("in the parameter file: ") + error.what());
        }
        continue;
      }
      AttributeReader param(file_, *p);
      const std::string name = param.String("name");
      const std::string value = param.String("value");
      param.Finish();
      if (name == "namespace" && !ros_namespace.empty()) {
        file_.Fail(*p, "a namespace param inside a pushed namespace; use one or the other");
      }
      node.arguments.push_back("--" + name);
      node.arguments.push_back(Substitute(*p, value, scope));
    }
    RequireExecutable(file_, e, exec, node.executable);
    description_.nodes.push_back(std::move(node));
  }

  // <executable cmd="PROGRAM ARGS..." name="N"> (ROS 2's tag for programs
  // that are not nodes, e.g. Fast DDS's "fast-discovery-server"): the command is split at
  // its own spaces, each word then substituted (CommandWords); PROGRAM is an
  // absolute path or found on PATH.
  // It runs in the environment around it plus its own <env>s, without a
  // namespace (it is not a ROS 2 node).
  void Executable(const tinyxml2::XMLElement& e, const Scope& scope) {
    AttributeReader attrs(file_, e);
    NodeLaunch node;
    const std::string cmd = attrs.String("cmd");
    const auto name = attrs.OptionalString("name");
    if (!ProcessAttributes(e, attrs, scope, node)) return;
    const auto words = CommandWords(cmd);
    const std::string program = words.empty() ? "" : Substitute(e, words.front(), scope);
    if (program.empty()) attrs.Fail("cmd is empty");
    for (size_t i = 1; i < words.size(); ++i) {
      node.arguments.push_back(Substitute(e, words[i], scope));
    }
    node.name = name ? Substitute(e, *name, scope) : program.substr(program.rfind('/') + 1);
    if (node.name.empty()) attrs.Fail("name is empty");
    AddNodeName(e, node.name);
    config::RequireChildNames(file_, e, {"env"});
    node.environment = scope.environment;
    for (const auto* p = e.FirstChildElement(); p != nullptr; p = p->NextSiblingElement()) {
      const auto [name, value] = Variable(*p, scope);
      SetVariable(node.environment, name, value);
    }
    node.executable = program.find('/') != std::string::npos ? program : FindOnPath(program);
    if (node.executable.empty()) {
      file_.Fail(e, "cmd '" + program + "' is not an executable on PATH");
    }
    RequireExecutable(file_, e, program, node.executable);
    description_.nodes.push_back(std::move(node));
  }

  // The attributes <node> and <executable> share: if, unless, output,
  // respawn, respawn_delay. Returns whether the process is launched; as in
  // ROS 2, the condition comes first and a process left out is not
  // substituted any further (its values may name what is only set where it
  // is wanted). Its attributes and children are still checked for unknown names.
  bool ProcessAttributes(const tinyxml2::XMLElement& e, AttributeReader& attrs, const Scope& scope,
                         NodeLaunch& node) {
    const bool active = Condition(e, attrs, scope);
    attrs.OptionalString("output");
    const auto respawn = attrs.OptionalString("respawn");
    const auto delay = attrs.OptionalString("respawn_delay");
    attrs.Finish();
    if (!active) {
      CheckChildrenLeftOut(e);
      return false;
    }
    if (respawn) node.respawn = Boolean(e, attrs, "respawn", *respawn, scope);
    if (delay) {
      const std::string text = Substitute(e, *delay, scope);
      char* end = nullptr;
      node.respawn_delay_s = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || !(node.respawn_delay_s >= 0.0) ||
          node.respawn_delay_s > 3600.0) {
        attrs.Fail("respawn_delay '" + text + "' is not a number of seconds in 0..3600");
      }
    }
    return true;
  }

  // The <param>s (of a <node>) and <env>s of a process left out: their
  // names and attributes checked as if it ran, nothing substituted.
  void CheckChildrenLeftOut(const tinyxml2::XMLElement& e) {
    const bool node = std::string(e.Name()) == "node";
    if (node) {
      config::RequireChildNames(file_, e, {"param", "env"});
    } else {
      config::RequireChildNames(file_, e, {"env"});
    }
    for (const auto* p = e.FirstChildElement(); p != nullptr; p = p->NextSiblingElement()) {
      AttributeReader child(file_, *p);
      if (std::string(p->Name()) == "param" && p->Attribute("from") != nullptr) {
        child.String("from");
      } else {
        child.String("name");
        child.String("value");
      }
      child.Finish();
    }
  }

  // A node's name after substitution: a ROS 2 node name (letters, digits and
  // '_', not starting with a digit), as it prefixes the node's output.
  std::string NodeName(const tinyxml2::XMLElement& e, const std::string& text, const Scope& scope) {
    const std::string name = Substitute(e, text, scope);
    if (!IsPlainName(name)) {
      file_.Fail(e, "name '" + name + "' is not a node name (letters, digits and '_', " +
                        "not starting with a digit)");
    }
    return name;
  }

  void AddNodeName(const tinyxml2::XMLElement& e, const std::string& name) {
    if (!node_names_.insert(name).second) file_.Fail(e, "duplicate node name '" + name + "'");
  }

  // The first executable file called `program` in PATH's folders ("" if none).
  static std::string FindOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::istringstream folders(path != nullptr ? path : "/usr/local/bin:/usr/bin:/bin");
    for (std::string folder; std::getline(folders, folder, ':');) {
      const std::string candidate = (folder.empty() ? "." : folder) + "/" + program;
      if (access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return "";
  }

  // A <set_env> or <env>: a variable name (letters, digits, '_', not starting
  // with a digit) and its substituted value.
  std::pair<std::string, std::string> Variable(const tinyxml2::XMLElement& e, const Scope& scope) {
    AttributeReader attrs(file_, e);
    const std::string name = attrs.String("name");
    const std::string value = attrs.String("value");
    attrs.Finish();
    if (!IsPlainName(name)) file_.Fail(e, "'" + name + "' is not an environment variable name");
    return {name, Substitute(e, value, scope)};
  }

  // The element's if= / unless= (ROS 2: true, false, 1 or 0 after
  // substitution; not both on one element).
  bool Condition(const tinyxml2::XMLElement& e, AttributeReader& attrs, const Scope& scope) {
    if (attrs.Has("if") && attrs.Has("unless")) {
      attrs.Fail("has both if and unless; ROS 2 launch takes one of them");
    }
    bool active = true;
    if (const auto text = attrs.OptionalString("if")) {
      active = Boolean(e, attrs, "if", *text, scope);
    }
    if (const auto text = attrs.OptionalString("unless")) {
      active = active && !Boolean(e, attrs, "unless", *text, scope);
    }
    return active;
  }

  // A boolean attribute's value after substitution: true or false in any case, 1 or 0.
  bool Boolean(const tinyxml2::XMLElement& e, AttributeReader& attrs, const char* key,
               const std::string& text, const Scope& scope) {
    // Any case, as ROS 2 launch reads it.
    std::string value = Substitute(e, text, scope);
    for (auto& c : value) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (value == "true" || value == "1") return true;
    if (value == "false" || value == "0") return false;
    attrs.Fail(std::string(key) + "=\"" + text + "\" is '" + value + "', not true, false, 1 or 0");
  }

  std::string Substitute(const tinyxml2::XMLElement& where, const std::string& text,
                         const Scope& scope) {
    return process::Substitute(file_, where, text, scope.vars, scope.environment, context_,
                               &shared_->total_bytes);
  }

  // Counts one more file read (an include, a parameter file, or the <arg>s
  // of an include left out) against the reading bounds, before it is read.
  void CountRead(const tinyxml2::XMLElement& e, const std::string& path) {
    CountFileRead(&file_, &e, path, context_, &shared_->files_read, &shared_->read_bytes);
  }

  // Namespaces nest as ROS 2's do: "robot1" inside "fleet" is "fleet/robot1";
  // a leading '/' makes a pushed namespace absolute.
  static std::string Join(const std::string& outer, const std::string& inner) {
    if (inner.empty()) return outer;
    if (inner.front() == '/' || outer.empty()) return inner.substr(inner.front() == '/' ? 1 : 0);
    return outer + "/" + inner;
  }

  const XmlFile& file_;
  const LaunchContext& context_;
  std::vector<std::string> includers_;  // the files that include this one, outermost first
  const std::set<std::string>* passed_ = nullptr;  // an included file's given arguments
  LaunchDescription description_;
  // What the file named on the command line shares with the files it
  // includes: the substituted bytes of them all (so includes cannot multiply
  // the bound), and the <arg> names declared in them, or in the files an
  // <include> left out would have read (NAME:=VALUE must name one of them).
  struct Shared {
    size_t total_bytes = 0;
    size_t files_read = 1;  // the file named on the command line
    size_t read_bytes = 0;
    std::set<std::string> declared;
  };
  Shared own_shared_;
  Shared* shared_;
  std::set<std::string> node_names_;
};

}  // namespace

LaunchDescription ReadLaunchFile(const std::string& path, const LaunchContext& context) {
  size_t files_read = 0, read_bytes = 0;
  CountFileRead(nullptr, nullptr, path, context, &files_read, &read_bytes);
  const auto file = XmlFile::Load(path);
  return LaunchReader(file, context, read_bytes).Read();
}

}  // namespace structloc::process
