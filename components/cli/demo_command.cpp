// "structloc demo": the main job a new user runs first. Until the simulation
// and localisation land it runs the component launch file for a few seconds
// and shows the components exchanging samples.
#include <iostream>

#include "launch_runner.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

int DemoCommand(const Invocation& inv) {
  process::ShutdownSignal shutdown;
  process::LaunchContext context{STRUCTLOC_SHARE_DIR, inv.bin_dir, {}};
  try {
    const auto description = process::ReadLaunchFile(
        std::string(STRUCTLOC_SHARE_DIR) + "/launch_xml/structloc.launch.xml", context);
    process::LaunchRunOptions options;
    options.duration_s = 5.0;
    return process::RunLaunch(description, options, shutdown);
  } catch (const std::exception& e) {
    std::cerr << "structloc demo: " << e.what() << std::endl;
    return 2;
  }
}

}  // namespace structloc::cli
