// A world model drawn into an occupancy grid, so that a building mapped for
// structloc can be handed to AMCL or Nav2 (`structloc map export`): every cell
// a wall touches is occupied (a closed supercover: a wall lying exactly on a
// cell border marks the cells on both sides, so that the wall's line stays the
// centre line of its cells), every cell a pillar's outline touches is
// occupied, a pillar's inside is unknown (no laser sees it), everything else
// free. DDS-free.
#pragma once

#include <cstddef>

#include "structloc/map_building/occupancy_grid.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

struct RasteriseOptions {
  static constexpr size_t kDefaultMaxCells = 100'000'000;

  double resolution_m = 0.05;  // cell size (map_saver's usual 5 cm)
  double margin_m = 0.5;       // free border around the world's bounds
  // Grids beyond this many cells are refused (a resolution in the wrong unit).
  size_t max_cells = kDefaultMaxCells;
};

// The grid covers the world's bounds plus the margin, its origin (yaw 0) on a
// whole multiple of the resolution, so that walls on round coordinates lie on
// cell borders and grids of the same building line up. Throws
// std::invalid_argument for a resolution or margin that is not positive /
// negative, or a grid beyond max_cells.
map_building::OccupancyGrid RasteriseWorld(const world_model::WorldModel& world,
                                           const RasteriseOptions& options);

// Marks as occupied every cell that the segment a-b touches (closed cells,
// with a tolerance of 1e-6 cells). Works in the grid's frame (any origin yaw).
void MarkSegment(map_building::OccupancyGrid& grid, const Eigen::Vector2d& a,
                 const Eigen::Vector2d& b);

// Marks as occupied every cell the circle's outline touches and as unknown
// every cell wholly inside it.
void MarkCircle(map_building::OccupancyGrid& grid, const Eigen::Vector2d& centre, double radius);

}  // namespace structloc::map_building
