// What the localisation saves while it runs and resumes from after a restart
// (as Nav2 AMCL saves its pose): the map -> odom correction and the pose
// variances, "map_to_odom X Y THETA VAR_X VAR_Y VAR_THETA" in one line, written
// atomically (unique temp file, fsync, rename) so that a crash never leaves half
// a file. A file that is unreadable anyway is reported and ignored by the
// component: the saved pose is a convenience, never a reason not to start.
// The correction, not the pose: the robot's odometry keeps running while the
// localisation is down, so correction * current odometry is where it is now.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::localisation {

struct SavedPose {
  geometry::Pose2D map_to_odom;
  Eigen::Vector3d variance{0.01, 0.01, 0.01};
};

// Throws std::runtime_error when the file cannot be written.
void SavePoseAtomically(const std::string& path, const SavedPose& saved);
// nullopt when the file does not exist; std::runtime_error naming the file when
// it is a folder, unreadable or malformed (empty, NaN, non-positive variances).
std::optional<SavedPose> LoadSavedPose(const std::string& path);

}  // namespace structloc::localisation
