// Occupancy grids in ROS map_server's format: a YAML file (image, resolution,
// origin, negate, occupied_thresh, free_thresh, mode) read with yaml-cpp, and
// the PGM or PNG image it names read and written with OpenCV. This is what
// slam_toolbox, gmapping, Cartographer and Nav2's map_saver write and what
// AMCL/Nav2 read. DDS-free.
#pragma once

#include <string>
#include <vector>

#include "structloc/map_building/occupancy_grid.hpp"

namespace structloc::map_formats {

// Loads a map_server YAML and its image into cells (-1/0/100 for mode
// "trinary", 0..100 for "scale", the raw value for "raw"). Throws
// config::ConfigError naming the file and what is wrong (missing or unreadable
// image, resolution not positive, unknown key or mode, thresholds out of
// order, image too large).
map_building::OccupancyGrid LoadGridMap(const std::string& yaml_path);

// Writes `<yaml_path>` and a PGM image beside it (same stem), trinary mode,
// negate 0, occupied_thresh 0.65, free_thresh 0.196 (map_saver's defaults), so
// that map_server, AMCL and Nav2 load it unchanged. Both files replace existing
// ones only when both were written; `inputs` are files that must not be
// overwritten. Throws std::runtime_error / config::ConfigError.
void SaveGridMap(const map_building::OccupancyGrid& grid, const std::string& yaml_path,
                 const std::vector<std::string>& inputs = {});

}  // namespace structloc::map_formats
