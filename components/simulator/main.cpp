// structloc_simulator: entry point of the simulator component.
#include "structloc/simulation_core/scenario_options.hpp"
#include "structloc/simulator/simulator_component.hpp"

int main(int argc, char** argv) {
  using structloc::config::ConfigError;
  std::vector<structloc::config::OptionSpec> specs = {
      {"scenario", true,
       "scenario XML (default: maps/scenarios/office_people.xml in structloc's data folder)"},
      {"time-scale", true,
       "simulated seconds per wall second, 0 = as fast as possible (default 1)"},
      {"seed", true, "override the scenario's seed"},
      {"exit-when-done", false, "exit when the scenario ends"},
      {"wait-for-subscribers", true,
       "hold the simulation clock until N readers of rt/scan and rt/odom are matched (default "
       "0)"},
      {"stand-s", true,
       "with --wait-for-subscribers: seconds the robot stands at its start, publishing odometry, "
       "after the readers matched (default 1)"}};
  const auto frame_options =
      structloc::dds_common::FrameIdOptions(structloc::dds_common::BaseFrame::kNamed);
  specs.insert(specs.end(), frame_options.begin(), frame_options.end());
  return structloc::dds_common::RunComponent(
      argc, argv, "simulator", specs,
      [](structloc::dds_common::Node& node, const structloc::config::CommandLine& cli,
         const structloc::dds_common::StopWait&) {
        auto scenario = structloc::simulation_core::LoadScenario(
            cli.PathOr("scenario", "maps/scenarios/office_people.xml"));
        if (cli.Has("seed")) {
          const long long seed = cli.Integer("seed", 0);
          if (seed < 0 || seed > 0xffffffffLL) throw ConfigError("--seed must be 0..4294967295");
          scenario.seed = static_cast<uint32_t>(seed);
        }
        structloc::simulator::SimulatorComponentOptions options;
        options.time_scale = cli.Number("time-scale", options.time_scale);
        if (!(options.time_scale >= 0.0 && options.time_scale <= 1000.0)) {
          throw ConfigError("--time-scale must be in [0, 1000]");
        }
        options.exit_when_done = cli.Has("exit-when-done");
        options.frames = structloc::dds_common::FrameIdsFrom(cli);
        options.wait_for_subscribers = static_cast<int>(cli.Integer("wait-for-subscribers", 0));
        if (options.wait_for_subscribers < 0)
          throw ConfigError("--wait-for-subscribers must be >= 0");
        options.stand_s = cli.Number("stand-s", options.stand_s);
        if (!(options.stand_s >= 0.0 && options.stand_s <= 3600.0))
          throw ConfigError("--stand-s must be in [0, 3600]");
        return std::make_unique<structloc::simulator::SimulatorComponent>(node, scenario, options);
      },
      structloc::simulation_core::PrintScenarioOptions);
}
