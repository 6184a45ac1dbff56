// The map builder's pipeline (see header).
#include "structloc/map_building/map_builder.hpp"

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
      walls.Add(id, map_points);
    }
    pillars.Add(id, scan.laser_pose, scan.points);
  }
  MapBuildResult result;
  result.walls = walls.Walls(result.wall_report);
  result.pillars = pillars.Pillars(result.pillar_report);
  result.corners_joined = JoinCorners(result.walls, options.corners);
  return result;
}

}  // namespace structloc::map_building
