// "structloc map export --map WORLD.xml --grid OUT.yaml [--resolution M]
// [--margin M]": a world map drawn into a map_server grid (YAML + PGM,
// map_saver's conventions), so that the building structloc localises in can
// be handed to AMCL or Nav2 unchanged. Walls and pillar outlines are occupied,
// pillar insides unknown, everything else free (see world_rasteriser.hpp).
#include <iostream>

#include "map_action.hpp"
#include "map_subcommands.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/map_building/world_rasteriser.hpp"
#include "structloc/map_formats/grid_map_file.hpp"
#include "structloc/world_model/world_model_xml.hpp"

namespace structloc::cli {

int MapExportCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"map", true, "world XML to export"},
      {"grid", true, "map_server YAML to write (the PGM goes beside it, same name)"},
      {"resolution", true, "cell size, m (default 0.05)"},
      {"margin", true, "free border around the map, m (default 0.5)"},
  };
  return RunMapAction(inv, "export", specs, [&](const config::CommandLine& cli) {
    const std::string map_path = cli.Required("map");
    const std::string grid_path = cli.Required("grid");
    map_building::RasteriseOptions options;
    options.resolution_m = cli.NumberIn("resolution", options.resolution_m, 1e-3, 100.0);
    options.margin_m = cli.NumberIn("margin", options.margin_m, 0.0, 1000.0);
    const auto world = world_model::LoadWorldModel(map_path);
    map_building::OccupancyGrid grid;
    try {
      grid = map_building::RasteriseWorld(world, options);
    } catch (const std::invalid_argument& e) {
      throw config::ConfigError(map_path + ": " + e.what());
    }
    map_formats::SaveGridMap(grid, grid_path, {map_path});
    size_t occupied = 0, unknown = 0;
    for (const auto v : grid.cells) {
      occupied += v == map_building::OccupancyGrid::kOccupied;
      unknown += v == map_building::OccupancyGrid::kUnknown;
    }
    std::cout << "structloc map export: " << map_path << ": " << world.Walls().size() << " walls, "
              << world.Cylinders().size() << " pillars -> " << grid.width << " x " << grid.height
              << " cells of " << grid.resolution_m << " m (origin " << grid.origin.x() << ", "
              << grid.origin.y() << "): " << occupied << " occupied, " << unknown
              << " unknown (inside pillars), " << grid.cells.size() - occupied - unknown
              << " free\n"
              << "  wrote " << grid_path << " and its PGM image\n";
    return 0;
  });
}

}  // namespace structloc::cli
