// "structloc simulate --scenario S.xml --out DIR [--seed N]": records a
// scenario without DDS (run.clf, truth.tum, initial_pose, encoders.csv).
#include <iostream>

#include "structloc/config/command_line.hpp"
#include "structloc/simulation_core/recorder.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

int SimulateCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"scenario", true, "scenario XML file (maps/scenarios/*.xml)"},
      {"out", true, "output folder (created)"},
      {"seed", true, "override the scenario's seed (0..4294967295)"},
      {"max-duration", true,
       "longest duration_s a scenario may ask for, in seconds (default " +
           std::to_string(static_cast<int>(simulation_core::ScenarioLimits::kDefaultMaxDurationS)) +
           ")"},
      {"max-walls", true,
       "most walls a world may have (default " +
           std::to_string(world_model::WorldLimits::kDefaultMaxWalls) +
           "); coordinates must lie within 100 km of the map origin"},
  };
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    simulation_core::ScenarioLimits limits;
    limits.max_duration_s = cli.NumberIn("max-duration", limits.max_duration_s, 1.0, 1e7);
    limits.world.max_walls = static_cast<size_t>(
        cli.IntegerIn("max-walls", static_cast<long long>(limits.world.max_walls), 1, 100000000));
    auto scenario = simulation_core::LoadScenario(cli.Required("scenario"), limits);
    if (cli.Has("seed"))
      scenario.seed = static_cast<uint32_t>(cli.IntegerIn("seed", 0, 0, 0xffffffffLL));
    const std::string out = cli.Required("out");
    const auto summary = simulation_core::RecordScenario(scenario, out);
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
