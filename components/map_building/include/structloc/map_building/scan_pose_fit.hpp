// How far each scan's recorded pose lies from the pose at which the map
// explains that scan best: every scan is fitted alone to the map's walls and
// pillars (point-to-surface Gauss-Newton from its recorded pose), and the fit's
// offset from the recorded pose is reported. A localiser evaluated against
// recorded poses (SLAM-corrected logs) cannot come closer to them than the map
// and the poses agree; scans whose best fit lies centimetres or degrees away
// mark where the reference and the map disagree, whichever of them is wrong.
// Used by `structloc map check --fit-poses`. DDS-free.
#pragma once

#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/map_building/posed_scans.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

struct ScanPoseFitOptions {
  double near_m = 0.1;       // readings this close to a wall or pillar take part, m
  int max_iterations = 30;   // Gauss-Newton steps (re-associating the readings each time)
  size_t min_readings = 30;  // scans with fewer readings near the map are not fitted
  // A weak pull towards the recorded pose, so that a direction the scan leaves
  // open (a corridor's length) stays where it was recorded.
  double prior_sigma_m = 0.5;
  double prior_sigma_rad = 0.5;
};

struct ScanPoseFit {
  size_t index = 0;         // the scan's number in the log
  bool fitted = false;      // enough readings near the map
  size_t readings = 0;      // near the map at the fitted pose
  geometry::Pose2D offset;  // fitted laser pose minus recorded: x, y (map frame), theta
};

// Throws std::invalid_argument when an option is out of range, naming it.
std::vector<ScanPoseFit> FitScanPoses(const world_model::WorldModel& world,
                                      const std::vector<PosedScan>& scans,
                                      const ScanPoseFitOptions& options);

}  // namespace structloc::map_building
