// Whether scans looked through a place the map builder would put a pillar:
// the free-space evidence against a pillar built from a person's sightings
// (pillar_finding.hpp). DDS-free.
#pragma once

#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/map_building/posed_scans.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

class SeeThroughCheck {
 public:
  // `scans` must outlive the check.
  explicit SeeThroughCheck(const std::vector<PosedScan>& scans);
  // The scans whose readings within half the pillar's radius of its
  // centre's bearing (at least one) all lie more than `margin_m` beyond its
  // far side: a beam there passed where the pillar would stand. Scans with
  // the laser inside the pillar, or no reading in that cone (no return, out
  // of range or of view), say nothing.
  size_t ScansSeeingThrough(const world_model::Cylinder& pillar, double margin_m) const;

 private:
  struct Scan {
    const PosedScan* scan;
    geometry::Pose2D from_map;  // map frame to the laser's
    double farthest_m;          // its farthest reading
    bool sweeps;                // its points' bearings rise in beam order
  };
  std::vector<Scan> scans_;
};

}  // namespace structloc::map_building
