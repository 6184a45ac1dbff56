// The map builder's pipeline (see header).
#include "structloc/map_building/map_builder.hpp"

#include <algorithm>

namespace structloc::map_building {

MapBuildResult BuildMap(const std::vector<PosedScan>& scans, const MapBuildOptions& options) {
  options.Validate();
  WallAccumulator walls(options.walls);
  PillarAccumulator pillars(options.pillars);
  std::vector<Eigen::Vector2d> map_points;
  for (const auto& scan : scans) {
    const auto id = static_cast<uint32_t>(scan.index);
    for (const auto& segment : ExtractScanSegments(scan.points, options.segments)) {
      map_points.clear();
      for (size_t i = segment.first; i < segment.last; ++i)
        map_points.push_back(scan.laser_pose.Apply(scan.points[i]));
      walls.Add(id, scan.laser_pose.Translation(), map_points);
    }
    pillars.Add(id, scan.laser_pose, scan.points);
  }
  MapBuildResult result;
  result.walls = walls.Walls(result.wall_report);
  result.pillars = pillars.Pillars(scans, result.pillar_report);
  // Short straight runs on a wide pillar's arc are its chords, not walls.
  const auto on_pillar = [&result, &options](const FittedWall& wall) {
    for (const auto& p : result.pillars) {
      const double reach = p.radius + options.walls.max_offset_m;
      if ((wall.a - p.centre).norm() < reach && (wall.b - p.centre).norm() < reach) return true;
    }
    return false;
  };
  const auto kept = std::remove_if(result.walls.begin(), result.walls.end(), on_pillar);
  result.walls_on_pillars = static_cast<size_t>(result.walls.end() - kept);
  result.walls.erase(kept, result.walls.end());
  result.shadow_walls = DropShadowWalls(result.walls, options.shadows);
  result.corners_joined = JoinCorners(result.walls, options.corners);
  result.short_after_joining = DropShortWalls(result.walls, options.walls.min_length_m);
  return result;
}

}  // namespace structloc::map_building
