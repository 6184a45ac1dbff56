// A point feature of the map (a corner, a pillar's centre, ...) where the
// odometric sensor pose says it should appear in the scan (thesis 3.5.4,
// 3.5.6). Each point kind places its own visible points with ExpectPoint, so
// that the clustering compares against precomputed numbers.
#pragma once

#include <Eigen/Core>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/localisation_core/association/map_error_memory.hpp"

namespace structloc::localisation_core {

struct ExpectedPoint {
  int model_index = 0;  // into the map's list of its kind
  int model_id = 0;
  Eigen::Vector2d world{0, 0};
  Eigen::Vector2d sensor{0, 0};  // in the sensor frame at the odometric pose
  double radius = 0.0;           // a pillar's; 0 for a corner
  int slot = 0;                  // the point's slot in the MapErrorMemory
  double map_error_scale = 1.0;  // factor on the map's share of a pairing's covariance
};

// Map point `model_index` of its kind (id `model_id`, at `world`, of
// `radius`) as seen from `sensor_pose`; its slot is first_slot + model_index
// (-1, no memory, while the kind has no slots: first_slot < 0), with that
// slot's map-error scale.
ExpectedPoint ExpectPoint(int model_index, int model_id, const Eigen::Vector2d& world,
                          double radius, int first_slot, const geometry::Pose2D& sensor_pose,
                          const MapErrorMemory& map_errors);

}  // namespace structloc::localisation_core
