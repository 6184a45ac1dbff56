// structloc_localisation: entry point of the localisation component.
#include "localisation_component.hpp"

int main(int argc, char** argv) {
  return structloc::dds::RunComponent(
      argc, argv, "localisation", {},
      [](structloc::dds::Node& node, const structloc::config::CommandLine&) {
        return std::make_unique<structloc::localisation::LocalisationComponent>(
            node, structloc::localisation::LocalisationComponentOptions{});
      });
}
