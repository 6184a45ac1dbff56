// A small strict parser for "--key value" and "--flag" command lines, shared by
// the components and the structloc CLI: unknown options are errors with a hint,
// numbers are parsed strictly (see strict_number.hpp), and "--help" is built in.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "structloc/config/strict_xml.hpp"

namespace structloc::config {

struct OptionSpec {
  std::string name;  // without the leading "--"
  bool takes_value = true;
  std::string help;
};

// Thrown by CommandLine for "--help" (a program may list "help" among its
// options so that its usage shows it); the program's entry point prints
// `usage` and exits 0.
// Not a std::exception, so that no "catch (const std::exception&)" on the way
// mistakes it for an error.
struct HelpRequested {
  std::string usage;
};

class CommandLine {
 public:
  // Throws ConfigError on an unknown option or a missing value, and
  // HelpRequested for "--help".
  CommandLine(int argc, const char* const* argv, int first, const std::vector<OptionSpec>& specs);

  bool Has(const std::string& name) const { return values_.count(name) != 0; }
  std::optional<std::string> Get(const std::string& name) const;
  std::string GetOr(const std::string& name, const std::string& fallback) const;
  // The option's value, else the shipped file `share_relative` in structloc's
  // data folder (see install_layout.hpp), looked up only when needed.
  std::string PathOr(const std::string& name, const std::string& share_relative) const;
  std::string Required(const std::string& name) const;
  double Number(const std::string& name, double fallback) const;
  // A number in [min, max]; the message names the bounds.
  double NumberIn(const std::string& name, double fallback, double min, double max) const;
  long long Integer(const std::string& name, long long fallback) const;
  long long IntegerIn(const std::string& name, long long fallback, long long min,
                      long long max) const;

  static std::string Usage(const std::vector<OptionSpec>& specs);

 private:
  std::map<std::string, std::string> values_;
};

}  // namespace structloc::config
