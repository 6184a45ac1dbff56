// Scans that looked through a pillar's place (see header).
#include "structloc/map_building/seen_through.hpp"

#include <cmath>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::map_building {
namespace {

bool SawThrough(const Eigen::Vector2d& centre, double radius, const PosedScan& scan,
                double margin_m) {
  const double d = centre.norm();
  if (d <= radius) return false;
  const double half_cone = std::asin(0.5 * radius / d);
  const double bearing = std::atan2(centre.y(), centre.x());
  const double beyond = d + radius + margin_m;
  size_t in_cone = 0;
  for (const auto& p : scan.points) {
    if (std::abs(geometry::WrapAngle(std::atan2(p.y(), p.x()) - bearing)) > half_cone) continue;
    if (p.squaredNorm() <= beyond * beyond) return false;
    ++in_cone;
  }
  return in_cone > 0;
}

}  // namespace

size_t ScansSeeingThrough(const world_model::Cylinder& pillar, const std::vector<PosedScan>& scans,
                          double margin_m) {
  size_t through = 0;
  for (const auto& scan : scans) {
    const Eigen::Vector2d centre = geometry::Inverse(scan.laser_pose).Apply(pillar.centre);
    if (SawThrough(centre, pillar.radius, scan, margin_m)) ++through;
  }
  return through;
}

}  // namespace structloc::map_building
