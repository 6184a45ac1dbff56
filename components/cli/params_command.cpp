// "structloc params [--check P.xml]": lists every localiser parameter (key,
// default, unit, valid values, meaning) from the one place the options are
// declared, or checks that a parameter file loads.
#include <iostream>

#include "command_line.hpp"
#include "localiser_options.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

int ParamsCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"check", true, "a <localisation_params> file to load and validate instead of listing"},
  };
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    if (const auto path = cli.Get("check")) {
      localisation::LoadLocaliserOptions(*path);
      std::cout << *path << ": valid\n";
      return 0;
    }
    localisation::PrintLocaliserOptions(std::cout);
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc params: " << e.what() << "\n";
    return 2;
  }
}

}  // namespace structloc::cli
