// What `structloc map check` says about a map and a recording, for the
// commands that check a map they hold (map check itself, and slam on the map
// it built): the counts, the disagreeing walls, and the picture.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "map_picture.hpp"
#include "structloc/map_building/map_check.hpp"
#include "structloc/map_building/posed_scans.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::cli {

// The check's figures (readings, share explained, their distance, the walls
// that disagree or were never seen), indented under a caller's headline.
void PrintMapCheckFindings(const world_model::WorldModel& world,
                           const map_building::MapCheckReport& report,
                           const map_building::MapCheckOptions& options, double max_range_m);

// The map over the readings, each wall coloured by its verdict and the
// readings no wall explains marked.
MapPicture MapCheckPicture(const std::string& title,
                           const std::vector<map_building::PosedScan>& scans,
                           const map_building::MapCheckReport& report,
                           const map_building::MapCheckOptions& options,
                           const std::vector<Eigen::Vector2d>& unexplained);

}  // namespace structloc::cli
