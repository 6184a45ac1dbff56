// structloc_simulator: entry point of the simulator component.
#include "simulator_component.hpp"

int main(int argc, char** argv) {
  using structloc::config::ConfigError;
  return structloc::dds::RunComponent(
      argc, argv, "simulator", {{"rate-hz", true, "sensor publication rate in Hz (default 10)"}},
      [](structloc::dds::Node& node, const structloc::config::CommandLine& cli) {
        structloc::simulator::SimulatorComponentOptions options;
        options.rate_hz = cli.Number("rate-hz", options.rate_hz);
        if (!(options.rate_hz > 0.0 && options.rate_hz <= 1000.0)) {
          throw ConfigError("--rate-hz must be in (0, 1000]");
        }
        return std::make_unique<structloc::simulator::SimulatorComponent>(node, options);
      });
}
