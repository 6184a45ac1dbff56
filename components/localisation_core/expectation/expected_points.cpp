// Expected points (see header).
#include "structloc/localisation_core/expectation/expected_points.hpp"

namespace structloc::localisation_core {

ExpectedPoint ExpectPoint(int model_index, int model_id, const Eigen::Vector2d& world,
                          double radius, int first_slot, const geometry::Pose2D& sensor_pose,
                          const MapErrorMemory& map_errors) {
  const int slot = first_slot < 0 ? -1 : first_slot + model_index;
  return {model_index,
          model_id,
          world,
          sensor_pose.ApplyInverse(world),
          radius,
          slot,
          map_errors.MapErrorScale(slot)};
}

}  // namespace structloc::localisation_core
