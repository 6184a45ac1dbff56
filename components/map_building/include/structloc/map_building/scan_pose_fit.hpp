// How far each scan's recorded pose lies from the pose at which the map
// explains that scan best: every scan is fitted alone to the map's walls and
// pillars (point-to-surface Gauss-Newton from its recorded pose), and the fit's
// offset from the recorded pose is reported. A localiser evaluated against
// recorded poses (SLAM-corrected logs) cannot come closer to them than the map
// and the poses agree; scans whose best fit lies centimetres or degrees away
// mark where the reference and the map disagree, whichever of them is wrong.
// Only readings within near_m of a surface take part, so a recorded pose off by
// much more than that finds a nearer, wrong fit: the offsets are meant for
// disagreements of centimetres and a few degrees. Used by `structloc map check
// --fit-poses`. DDS-free.
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
  bool fitted = false;      // at least min_readings near the map at the fitted pose
  bool converged = false;   // the last step was below 0.01 mm and 0.01 mrad
  int iterations = 0;       // steps taken
  size_t readings = 0;      // near the map at the fitted pose
  geometry::Pose2D offset;  // fitted laser pose minus recorded: x, y (map frame), theta
};

// Throws std::invalid_argument when an option is out of range, naming it.
std::vector<ScanPoseFit> FitScanPoses(const world_model::WorldModel& world,
                                      const std::vector<PosedScan>& scans,
                                      const ScanPoseFitOptions& options);

// The offsets of the fits that converged: median, 90 % (Quantile) and max of
// the position offset's length and of the heading offset's magnitude.
struct ScanPoseFitSummary {
  size_t scans = 0, fitted = 0, converged = 0;
  double median_shift_m = 0, p90_shift_m = 0, max_shift_m = 0;
  double median_turn_rad = 0, p90_turn_rad = 0, max_turn_rad = 0;
  std::vector<size_t> farthest;  // indices into the fits, farthest in position first
};
ScanPoseFitSummary SummarisePoseFits(const std::vector<ScanPoseFit>& fits, size_t farthest);

}  // namespace structloc::map_building
