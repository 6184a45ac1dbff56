// `structloc map build`: a world model of walls, corners and pillars from a
// recording whose scan poses are known (SLAM-corrected), after the map building
// the thesis proposes in 6.5.5. Per scan: straight segments (scan_segments.hpp)
// and arcs (pillar_finding.hpp); across scans: segments on one line merged and
// refitted into walls (wall_merging.hpp); wall ends pulled together where walls
// meet, so that corners are derived there (wall_fitting.hpp). DDS-free.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "structloc/map_building/pillar_finding.hpp"
#include "structloc/map_building/posed_scans.hpp"
#include "structloc/map_building/scan_segments.hpp"
#include "structloc/map_building/shadow_walls.hpp"
#include "structloc/map_building/wall_fitting.hpp"
#include "structloc/map_building/wall_merging.hpp"

namespace structloc::map_building {

// Every option of the map builder; the defaults suit a 180 deg SICK-like
// laser (1 cm noise, 0.5-1 deg beams) indoors. Loaded from a
// <map_build_params> file (LoadMapBuildOptions).
struct MapBuildOptions {
  PosedScanOptions scans;
  ScanSegmentOptions segments;
  WallMergeOptions walls;
  ShadowWallOptions shadows;
  CornerJoinOptions corners;
  PillarOptions pillars;
  // Throws std::invalid_argument naming the section and key of the first bad value.
  void Validate() const;
};

MapBuildOptions LoadMapBuildOptions(const std::string& path);
void PrintMapBuildOptions(std::ostream& out);
// A complete <map_build_params> file (every key) of the file at `path` as
// loaded, with what it takes from its base.
void WriteExpandedMapBuildOptions(const std::string& path, std::ostream& out);

struct MapBuildResult {
  std::vector<FittedWall> walls;  // with their support, in the world's wall order
  std::vector<world_model::Cylinder> pillars;
  size_t corners_joined = 0;
  size_t walls_on_pillars = 0;  // chords of a pillar's arc, dropped
  size_t shadow_walls = 0;      // shadows of longer walls, dropped (shadow_walls.hpp)
  // Shortened below walls.min_length_m by joining their corners, dropped.
  size_t short_after_joining = 0;
  WallMergeReport wall_report;
  PillarReport pillar_report;
};

// Builds the walls and pillars of the scans (which must hold poses in the map frame).
MapBuildResult BuildMap(const std::vector<PosedScan>& scans, const MapBuildOptions& options);

}  // namespace structloc::map_building
