// Whether scans looked through a place the map builder would put a pillar:
// the free-space evidence against a pillar built from a person's sightings
// (pillar_finding.hpp). DDS-free.
#pragma once

#include <vector>

#include "structloc/map_building/posed_scans.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

// The scans whose readings within half the pillar's radius of its centre's
// bearing (at least one) all lie more than `margin_m` beyond its far side: a
// beam there passed where the pillar would stand. Scans with the laser
// inside the pillar, or no reading in that cone (no return, out of range or
// of view), say nothing.
size_t ScansSeeingThrough(const world_model::Cylinder& pillar, const std::vector<PosedScan>& scans,
                          double margin_m);

}  // namespace structloc::map_building
