// Where a robot without a pose is (no initial pose given, no saved state, or
// a request to relocalise): each incoming scan goes to the global localiser
// until one gives a "found" pose, never an ambiguous or unfound one; that pose
// (the laser's, turned into the robot's with the sensor mount) becomes the
// initial pose at the scan's stamp. The localisation component runs it;
// DDS-free.
#pragma once

#include <optional>

#include "structloc/localisation_core/global_localiser.hpp"
#include "structloc/localisation_core/session_inbox.hpp"
#include "structloc/localisation_core/session_scan.hpp"

namespace structloc::localisation_core {

class GlobalStart {
 public:
  // `covariance`: of a pose found (the tracker's initial covariance).
  GlobalStart(const world_model::WorldModel& world, const geometry::Pose2D& sensor_mount,
              const Eigen::Matrix3d& covariance, const GlobalLocaliserOptions& options = {});

  struct Attempt {
    GlobalResult result;                    // laser poses
    std::optional<InitialPoseInput> found;  // the robot's initial pose, when found
  };
  Attempt Try(const SessionScan& scan) const;

 private:
  GlobalLocaliser search_;
  geometry::Pose2D mount_;
  Eigen::Matrix3d covariance_;
};

}  // namespace structloc::localisation_core
