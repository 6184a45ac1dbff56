// "structloc simulate --scenario S.xml --out DIR [--seed N]": records a
// scenario without DDS (run.clf, truth.tum, initial_pose, encoders.csv).
#include <iostream>

#include "command_line.hpp"
#include "recorder.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

int SimulateCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"scenario", true, "scenario XML file (maps/scenarios/*.xml)"},
      {"out", true, "output folder (created)"},
      {"seed", true, "override the scenario's seed"},
  };
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    auto scenario = simulation::LoadScenario(cli.Required("scenario"));
    if (cli.Has("seed")) {
      const long long seed = cli.Integer("seed", 0);
      if (seed < 0 || seed > 0xffffffffLL)
        throw config::ConfigError("--seed must be 0..4294967295");
      scenario.seed = static_cast<uint32_t>(seed);
    }
    const std::string out = cli.Required("out");
    const auto summary = simulation::RecordScenario(scenario, out);
    std::cout << "structloc simulate: " << scenario.name << " (seed " << scenario.seed
              << "): " << summary.duration_s << " s simulated, " << summary.scans << " scans, "
              << summary.odometry_lines << " odometry lines; odometry-only error at the end "
              << summary.odometry_final_error_m << " m\n"
              << "  wrote " << out << "/run.clf, truth.tum, initial_pose, encoders.csv\n";
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc simulate: " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc simulate: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
