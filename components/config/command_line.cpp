// Implementation of the strict command-line parser.
#include "command_line.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace structloc::config {

CommandLine::CommandLine(int argc, const char* const* argv, int first,
                         const std::vector<OptionSpec>& specs) {
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) throw ConfigError("unexpected argument '" + arg + "'");
    const std::string name = arg.substr(2);
    const OptionSpec* spec = nullptr;
    for (const auto& s : specs) {
      if (s.name == name) spec = &s;
    }
    if (spec == nullptr) throw ConfigError("unknown option '" + arg + "'\n" + Usage(specs));
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

std::string CommandLine::Required(const std::string& name) const {
  auto value = Get(name);
  if (!value) throw ConfigError("missing required option --" + name);
  return *value;
}

double CommandLine::Number(const std::string& name, double fallback) const {
  auto raw = Get(name);
  if (!raw) return fallback;
  char* end = nullptr;
  const double value = std::strtod(raw->c_str(), &end);
  if (end == raw->c_str() || *end != '\0' || !std::isfinite(value)) {
    throw ConfigError("option --" + name + " '" + *raw + "' is not a finite number");
  }
  return value;
}

long long CommandLine::Integer(const std::string& name, long long fallback) const {
  auto raw = Get(name);
  if (!raw) return fallback;
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(raw->c_str(), &end, 10);
  if (end == raw->c_str() || *end != '\0' || errno == ERANGE) {
    throw ConfigError("option --" + name + " '" + *raw + "' is not an integer");
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
