// "structloc launch FILE.launch.xml [NAME:=VALUE ...] [--duration S]": starts
// the components a launch file names, as ros2 launch would.
#include <iostream>

#include "launch_runner.hpp"
#include "strict_xml.hpp"
#include "subcommands.hpp"

#ifndef STRUCTLOC_SHARE_DIR
#error "STRUCTLOC_SHARE_DIR must be defined by the build"
#endif

namespace structloc::cli {

int LaunchCommand(const Invocation& inv) {
  process::ShutdownSignal shutdown;
  if (inv.argc < 3) {
    std::cerr << "usage: structloc launch FILE.launch.xml [NAME:=VALUE ...] [--duration S]\n";
    return 2;
  }
  process::LaunchContext context{STRUCTLOC_SHARE_DIR, inv.bin_dir, {}};
  process::LaunchRunOptions options;
  try {
    for (int i = 3; i < inv.argc; ++i) {
      const std::string arg = inv.argv[i];
      const auto sep = arg.find(":=");
      if (arg == "--duration" && i + 1 < inv.argc) {
        options.duration_s = std::stod(inv.argv[++i]);
      } else if (sep != std::string::npos && sep > 0) {
        context.overrides[arg.substr(0, sep)] = arg.substr(sep + 2);
      } else {
        throw config::ConfigError("unexpected argument '" + arg + "'");
      }
    }
    const auto description = process::ReadLaunchFile(inv.argv[2], context);
    return process::RunLaunch(description, options, shutdown);
  } catch (const std::exception& e) {
    std::cerr << "structloc launch: " << e.what() << std::endl;
    return 2;
  }
}

}  // namespace structloc::cli
