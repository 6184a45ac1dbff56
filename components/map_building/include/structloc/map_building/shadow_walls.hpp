// A surface seen on several passes whose SLAM poses disagree by a few
// centimetres comes out of the merge as two nearly parallel walls a few
// centimetres apart. Localising against both pulls every pose towards the
// wrong copy (on the Freiburg 079 recording 2 cm along the direction of
// travel, every scan): the shorter of two such walls is a shadow of the
// longer and is dropped. The two faces of a partition are seen from opposite
// sides and both stay (walls whose viewpoint is not known are judged by
// geometry alone).
#pragma once

#include <vector>

#include "structloc/map_building/wall_fitting.hpp"

namespace structloc::map_building {

struct ShadowWallOptions {
  double max_offset_m = 0.2;    // both ends of the shorter wall this close to the longer's line
  double max_angle_rad = 0.07;  // ... the two within this angle (4 deg)
  double min_overlap = 0.5;     // ... and at least this share of it alongside the longer
};

// Drops shadows in place (the longest wall of each family stays); returns how many.
size_t DropShadowWalls(std::vector<FittedWall>& walls, const ShadowWallOptions& options);

}  // namespace structloc::map_building
