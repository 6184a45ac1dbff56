// Occupancy grids in ROS map_server's format: a YAML file (image, resolution,
// origin, negate, occupied_thresh, free_thresh, mode) read with yaml-cpp, and
// the PGM or PNG image it names read and written with OpenCV. This is what
// slam_toolbox, gmapping, Cartographer and Nav2's map_saver write and what
// AMCL/Nav2 read. DDS-free.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "structloc/map_building/occupancy_grid.hpp"

namespace structloc::map_formats {

// The grid type is the map builder's; this file only reads and writes it.
using map_building::OccupancyGrid;

// A map_server YAML's `mode`: how grey levels became cell values.
enum class GridMapMode { kTrinary, kScale, kRaw };

// How strictly a map_server YAML is read, and how large a grid may be.
struct GridMapReadOptions {
  // 4000 x 4000 cells: 200 m square at 5 cm. Importing a grid this large
  // takes under a second and 300 MB; a larger one needs a larger limit.
  static constexpr size_t kDefaultMaxCells = 16'000'000;

  // Cells (width * height) beyond which the image is refused before it is
  // decoded (the PGM or PNG header is read first): a guard against a wrong or
  // hostile file taking all memory (a 1 MB PNG can hold 10^9 cells).
  size_t max_cells = kDefaultMaxCells;
  // map_server and Nav2 read only image, resolution, origin, negate,
  // occupied_thresh, free_thresh and mode, and ignore every other key. We
  // refuse other keys by default, so that a misspelt key ("ocupied_thresh")
  // is not silently replaced by its default; true ignores them as ROS does
  // (for YAMLs that carry extra keys for other tools).
  bool ignore_unknown_keys = false;
};

// Loads a map_server YAML and its image into cells. Required keys: image
// (relative to the YAML's folder unless absolute), resolution (m per cell,
// > 0) and origin ([x, y, yaw]); optional with map_saver's defaults: negate
// (0), occupied_thresh (0.65), free_thresh (0.196), mode ("trinary").
// Values as map_server computes them: p = (255 - x) / 255 (x / 255 when
// negated) from the grey level x (colour channels averaged, alpha ignored);
// "trinary": 100 when p > occupied_thresh, 0 when p < free_thresh, else -1;
// "scale": the same but 99 * (p - free) / (occupied - free) in between, and -1
// where the alpha channel is not opaque; "raw": x itself (0..100, 255 for -1,
// as map_saver writes raw maps). Throws config::ConfigError naming the file and
// what is wrong (unreadable YAML, missing or unknown key, resolution not
// positive, unknown mode, thresholds outside [0, 1] or free >= occupied,
// missing or unreadable image, image too large, empty image). A PGM's grey
// levels are read against its maxval (white), a 16-bit PNG's against 65535.
// The image must be a PNG or a PGM (map_server's formats, whose size is read
// from the header before anything is decoded); other formats are refused.
// `source`, when given, receives the YAML's mode (with "trinary" and "scale"
// the thresholds are applied already: only 100 is occupied, only 0 free) and
// the image's path, an input too.
struct GridMapSource {
  GridMapMode mode = GridMapMode::kTrinary;
  std::string image_path;  // resolved against the YAML's folder
};
OccupancyGrid LoadGridMap(const std::string& yaml_path, const GridMapReadOptions& options = {},
                          GridMapSource* source = nullptr);

// Writes `<yaml_path>` and a PGM image beside it (same stem), trinary mode,
// negate 0, occupied_thresh 0.65, free_thresh 0.196 (map_saver's defaults), so
// that map_server, AMCL and Nav2 load it unchanged: cells >= 65 are black (0),
// cells 0..19 white (254), the rest (unknown, and values in between) grey
// (205), which LoadGridMap reads back as 100, 0 and -1. Both files replace
// existing ones only when both were written; `inputs` are files that must not
// be overwritten. Throws std::runtime_error / config::ConfigError.
void SaveGridMap(const OccupancyGrid& grid, const std::string& yaml_path,
                 const std::vector<std::string>& inputs = {});

}  // namespace structloc::map_formats
