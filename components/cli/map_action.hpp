// How every `structloc map` action turns its options and errors into what a
// user sees: a mistake in the options prints the message and the action's
// options (exit 2); a problem with an input file prints the message naming it
// (exit 2); any other failure prints its message (exit 1).
#pragma once

#include <iostream>
#include <optional>
#include <vector>

#include "structloc/config/command_line.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

// Parses the options after "structloc map ACTION" and runs `body(cli)`, which
// returns the exit code.
template <class Body>
int RunMapAction(const Invocation& inv, const char* action,
                 const std::vector<config::OptionSpec>& specs, Body body) {
  const std::string name = std::string("structloc map ") + action;
  std::optional<config::CommandLine> cli;
  try {
    cli.emplace(inv.argc, inv.argv, 3, specs);
  } catch (const config::ConfigError& e) {
    std::cerr << name << ": " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  }
  try {
    return body(*cli);
  } catch (const config::ConfigError& e) {
    std::cerr << name << ": " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << name << ": " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
