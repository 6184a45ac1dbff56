// "structloc map grid --log LOG --out GRID.yaml [--resolution M]": a log-odds
// occupancy grid ray-cast from a recording whose scan poses are corrected,
// written in ROS map_server's format (YAML + PGM): a map for AMCL or Nav2, and
// the independent grid on which `structloc map import --grid` is checked.
#include <iostream>

#include "map_action.hpp"
#include "map_subcommands.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/map_building/log_odds_grid.hpp"
#include "structloc/map_formats/grid_map_file.hpp"

namespace structloc::cli {

int MapGridCommand(const Invocation& inv) {
  const map_building::LogOddsGridOptions defaults;
  const map_building::PosedScanOptions scan_defaults;
  const std::vector<config::OptionSpec> specs = {
      {"log", true, "CARMEN log whose scan poses are corrected (e.g. by SLAM), .gz or plain"},
      {"scans", true,
       "use only the scans FIRST:LAST of the log (numbers from 0, LAST not included; default: "
       "all), e.g. to build from one part and check on another"},
      {"out", true, "map_server YAML to write (the PGM image is written beside it)"},
      {"resolution", true, "cell size, m (default 0.05)"},
      {"max-range", true, "readings farther than this are left out, m (default 20)"},
  };
  return RunMapAction(inv, "grid", specs, [&](const config::CommandLine& cli) {
    const std::string log_path = cli.Required("log");
    const std::string out_path = cli.Required("out");
    map_building::LogOddsGridOptions options;
    options.resolution_m = cli.NumberIn("resolution", defaults.resolution_m, 1e-3, 10.0);
    map_building::PosedScanOptions scan_options;
    scan_options.max_range_m =
        cli.NumberIn("max-range", scan_defaults.max_range_m, scan_defaults.min_range_m + 0.01, 1e3);
    const auto range = map_building::ParseScanRange(cli.GetOr("scans", ":"));
    auto log = map_building::ReadPosedScans(log_path, scan_options);
    map_building::KeepScans(log, range.first, range.second);
    std::cerr << log_formats::MalformedLinesText(log.reader, log_path);
    const auto grid = map_building::RayCastGrid(log.scans, options);
    map_formats::SaveGridMap(grid, out_path, {log_path});
    size_t occupied = 0, free = 0;
    for (const auto c : grid.cells) {
      occupied += c == map_building::OccupancyGrid::kOccupied;
      free += c == map_building::OccupancyGrid::kFree;
    }
    std::cout << "structloc map grid: " << log.scans.size() << " scans, "
              << log.readings - log.out_of_range << " readings ray-cast into " << grid.width
              << " x " << grid.height << " cells of " << options.resolution_m << " m: " << occupied
              << " occupied, " << free << " free, " << grid.cells.size() - occupied - free
              << " unknown\n  wrote " << out_path << "\n";
    return 0;
  });
}

}  // namespace structloc::cli
