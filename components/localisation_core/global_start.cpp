// Global start-up of a robot without a pose (see header).
#include "structloc/localisation_core/global_start.hpp"

#include <cmath>

namespace structloc::localisation_core {

GlobalStart::GlobalStart(const world_model::WorldModel& world, const geometry::Pose2D& sensor_mount,
                         const Eigen::Matrix3d& covariance, const GlobalLocaliserOptions& options)
    : search_(world, options), mount_(sensor_mount), covariance_(covariance) {}

GlobalStart::Attempt GlobalStart::Try(const SessionScan& scan) const {
  const auto& g = scan.geometry;
  const double max_range = g.range_max > 0.0 ? g.range_max - 1e-3 : INFINITY;
  Attempt attempt;
  attempt.result = search_.Locate(
      ScanPointsInLaserFrame(scan.ranges, g.angle_min, g.angle_increment, g.range_min, max_range));
  if (attempt.result.decision == GlobalDecision::kFound) {
    attempt.found = InitialPoseInput{
        g.stamp, geometry::Compose(attempt.result.best->pose, geometry::Inverse(mount_)),
        covariance_};
  }
  return attempt;
}

}  // namespace structloc::localisation_core
