// The pictures of `structloc map build` and `map check`: a world map over the
// recording's readings (map frame), walls optionally coloured one by one.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "structloc/config/output_file.hpp"
#include "structloc/map_building/posed_scans.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::cli {

struct MapPicture {
  std::string title;
  std::vector<Eigen::Vector2d> readings;  // drawn light grey
  std::vector<Eigen::Vector2d> marked;    // drawn red (e.g. readings no wall explains)
  std::vector<cv::Scalar> wall_colours;   // one per wall, or empty for the usual colour
  std::vector<std::pair<cv::Scalar, std::string>> legend;
};

// Readings of every `step`-th scan in the map frame, for a picture.
std::vector<Eigen::Vector2d> MapFrameReadings(const std::vector<map_building::PosedScan>& scans,
                                              size_t step);

// Draws the picture and writes it through `file` (the caller commits it with
// the run's other outputs); throws std::runtime_error.
void WriteMapPicture(config::OutputFile& file, const world_model::WorldModel& world,
                     const MapPicture& picture);

}  // namespace structloc::cli
