// The pose the localisation saves while it runs and resumes from after a
// restart (as Nav2 AMCL does): "x y theta var_x var_y var_theta" in one line,
// map frame, written atomically (temp file + rename) so that a crash never
// leaves half a file.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "pose2d.hpp"

namespace structloc::localisation {

struct SavedPose {
  geometry::Pose2D pose;
  Eigen::Vector3d variance{0.01, 0.01, 0.01};
};

// Throws std::runtime_error when the file cannot be written.
void SavePoseAtomically(const std::string& path, const SavedPose& saved);
// nullopt when the file does not exist; std::runtime_error when it is malformed.
std::optional<SavedPose> LoadSavedPose(const std::string& path);

}  // namespace structloc::localisation
