// An occupancy grid ray-cast from a recording whose scan poses are corrected:
// every reading lowers the log-odds of the cells its beam crosses and raises the
// one it ends in (the usual inverse sensor model of occupancy mapping), and the
// result is thresholded as map_saver does. The evidence of the whole recording
// counts: the log-odds are not clamped by default. A clamp makes a cell's state
// the verdict of its last few passes, and on a recording whose passes disagree
// by a few centimetres (SLAM-corrected poses) the last pass then decides where
// a wall's cells lie (Freiburg 079: the mean offset of each imported wall from
// the readings that see it was 18 mm RMS from a grid clamped at +-4, 13 mm from
// the unclamped grid). `structloc map grid` writes it as a map_server map:
// the independent grid that `map import --grid` is checked on, and a map for
// AMCL/Nav2 users. DDS-free.
#pragma once

#include <limits>
#include <vector>

#include "structloc/map_building/occupancy_grid.hpp"
#include "structloc/map_building/posed_scans.hpp"

namespace structloc::map_building {

struct LogOddsGridOptions {
  double resolution_m = 0.05;
  double hit_log_odds = 0.85;   // ln(0.7 / 0.3): a beam ends in the cell
  double miss_log_odds = -0.4;  // ln(0.4 / 0.6): a beam passes through the cell
  // Clamps (none by default, and `map grid` sets none): with them a cell can
  // change its mind, as a map of a changing scene needs, and the newest
  // passes outvote the older ones.
  double min_log_odds = -std::numeric_limits<double>::infinity();
  double max_log_odds = std::numeric_limits<double>::infinity();
  double occupied_probability = 0.65;  // map_saver's thresholds
  double free_probability = 0.196;
  double margin_m = 1.0;   // around the readings and poses
  double max_cells = 2e8;  // larger grids are refused (wrong unit or a runaway pose)
};

// Throws std::invalid_argument for bad options or a grid above max_cells.
map_building::OccupancyGrid RayCastGrid(const std::vector<PosedScan>& scans,
                                        const LogOddsGridOptions& options);

}  // namespace structloc::map_building
