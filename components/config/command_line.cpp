// Implementation of the strict command-line parser.
#include "structloc/config/command_line.hpp"
#include "structloc/config/install_layout.hpp"

#include <sstream>

#include "structloc/config/strict_number.hpp"

namespace structloc::config {
namespace {

// "structloc replay" for argv = {"/path/structloc", "replay", ...} and first = 2.
std::string ProgramName(const char* const* argv, int first) {
  std::string name;
  for (int i = 0; i < first; ++i) {
    std::string part = argv[i];
    if (i == 0) part = part.substr(part.find_last_of('/') + 1);
    name += (i == 0 ? "" : " ") + part;
  }
  return name;
}

}  // namespace

CommandLine::CommandLine(int argc, const char* const* argv, int first,
                         const std::vector<OptionSpec>& specs) {
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help") {
      throw HelpRequested{"usage: " + ProgramName(argv, first) + " [options]\n" + Usage(specs)};
    }
    if (arg.rfind("--", 0) != 0) throw ConfigError("unexpected argument '" + arg + "'");
    const std::string name = arg.substr(2);
    const OptionSpec* spec = nullptr;
    for (const auto& s : specs) {
      if (s.name == name) spec = &s;
    }
    if (spec == nullptr)
      throw ConfigError("unknown option '" + arg + "' (--help lists the options)");
    if (!spec->takes_value) {
      // Flags may carry an explicit true/false (launch files always pass a value).
      const std::string next = i + 1 < argc ? argv[i + 1] : "";
      if (next == "true" || next == "false") ++i;
      if (next != "false") values_[name] = "true";
      continue;
    }
    if (i + 1 >= argc) throw ConfigError("option '" + arg + "' needs a value");
    values_[name] = argv[++i];
  }
}

std::optional<std::string> CommandLine::Get(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string CommandLine::GetOr(const std::string& name, const std::string& fallback) const {
  return Get(name).value_or(fallback);
}

std::string CommandLine::PathOr(const std::string& name, const std::string& share_relative) const {
  const auto value = Get(name);
  return value ? *value : SharePath(share_relative);
}

std::string CommandLine::Required(const std::string& name) const {
  auto value = Get(name);
  if (!value) throw ConfigError("missing required option --" + name);
  return *value;
}

double CommandLine::Number(const std::string& name, double fallback) const {
  auto raw = Get(name);
  if (!raw) return fallback;
  const auto value = ParseFiniteDouble(*raw);
  if (!value) throw ConfigError("option --" + name + " '" + *raw + "' is not a finite number");
  return *value;
}

double CommandLine::NumberIn(const std::string& name, double fallback, double min,
                             double max) const {
  const double value = Number(name, fallback);
  if (value < min || value > max) {
    std::ostringstream msg;
    msg << "option --" << name << " " << value << " must be from " << min << " to " << max;
    throw ConfigError(msg.str());
  }
  return value;
}

long long CommandLine::Integer(const std::string& name, long long fallback) const {
  auto raw = Get(name);
  if (!raw) return fallback;
  const auto value = ParseInteger(*raw);
  if (!value) throw ConfigError("option --" + name + " '" + *raw + "' is not an integer");
  return *value;
}

long long CommandLine::IntegerIn(const std::string& name, long long fallback, long long min,
                                 long long max) const {
  const long long value = Integer(name, fallback);
  if (value < min || value > max) {
    throw ConfigError("option --" + name + " " + std::to_string(value) + " must be from " +
                      std::to_string(min) + " to " + std::to_string(max));
  }
  return value;
}

std::string CommandLine::Usage(const std::vector<OptionSpec>& specs) {
  std::ostringstream out;
  out << "options:\n";
  for (const auto& s : specs) {
    out << "  --" << s.name << (s.takes_value ? " VALUE" : "") << "  " << s.help << "\n";
  }
  return out.str();
}

}  // namespace structloc::config
