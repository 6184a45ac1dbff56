// Whether a beam passes through a wall, traced on a grid's distance field:
// the whole-scan check asks it for every beam of every scan, and global
// localisation for every reading it ranks, so it skips the samples the
// field shows clear (the result is that of testing every sample). Its own
// file so that the skip is tested against every sample on any field.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace structloc::localisation_core {

// A grid's cells (row major, `width` x `height`, cell (0, 0) with its lower
// left corner at (x0, y0), cells of `resolution_m`), each holding the
// distance in whole cells (floored, at most 255) from its centre to the
// nearest wall cell's centre: 0 for a wall cell.
struct WallDistanceField {
  const std::vector<uint8_t>* cells = nullptr;
  int width = 0;
  int height = 0;
  double x0 = 0.0;
  double y0 = 0.0;
  double resolution_m = 0.0;
};

// The samples every half cell from `from` to `to` (ends excluded), as many
// as fit, tested in order for lying in a wall cell (true) until one leaves
// the grid (false).
bool CrossesWall(const WallDistanceField& field, const Eigen::Vector2d& from,
                 const Eigen::Vector2d& to);

}  // namespace structloc::localisation_core
