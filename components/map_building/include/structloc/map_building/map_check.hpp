// `structloc map check`: how well a map agrees with a recording whose scan
// poses are corrected. Every reading is put in the map frame and given to the
// nearest wall or pillar within reach; per wall: how many readings hit it, from
// how many scans, and how far they lie from it (median, RMS, and the mean signed
// offset towards the laser, which says which way to move the wall). Walls no
// reading hits are "never seen"; readings no surface explains are counted (they
// are furniture, people, or walls the map lacks). DDS-free.
#pragma once

#include <vector>

#include "structloc/map_building/posed_scans.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

struct MapCheckOptions {
  double near_m = 0.1;         // a reading this close to a wall or pillar hits it
  double max_median_m = 0.03;  // walls whose readings lie farther (median) disagree
  size_t min_readings = 10;    // walls hit by fewer readings are "rarely seen"
};

struct SurfaceAgreement {
  size_t readings = 0;
  size_t scans = 0;
  double median_m = 0.0;  // median |distance| of its readings
  double rms_m = 0.0;
  double mean_offset_m = 0.0;  // mean signed distance, > 0: readings in front of it (laser side)
  bool disagrees = false;      // seen, and its median above max_median_m
};

struct MapCheckReport {
  size_t scans = 0;
  size_t readings = 0;    // within the range limits
  size_t explained = 0;   // within near_m of a wall or pillar
  double median_m = 0.0;  // over the explained readings
  double p90_m = 0.0;
  double rms_m = 0.0;
  std::vector<SurfaceAgreement> walls;    // one per world.Walls()
  std::vector<SurfaceAgreement> pillars;  // one per world.Cylinders()
  size_t walls_never_seen = 0;
  size_t walls_rarely_seen = 0;  // seen, but by fewer than min_readings readings
  size_t walls_disagreeing = 0;
  double ExplainedShare() const {
    return readings == 0 ? 0.0 : static_cast<double>(explained) / static_cast<double>(readings);
  }
};

// `unexplained`, when given, receives the map-frame readings no surface explains.
MapCheckReport CheckMap(const world_model::WorldModel& world, const std::vector<PosedScan>& scans,
                        const MapCheckOptions& options,
                        std::vector<Eigen::Vector2d>* unexplained = nullptr);

}  // namespace structloc::map_building
