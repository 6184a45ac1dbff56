// Reads TUM trajectories ("t x y z qx qy qz qw" per line, '#' comments) as
// planar poses; malformed lines are errors naming file and line.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::log_formats {

struct StampedPose {
  double stamp;
  geometry::Pose2D pose;
};

std::vector<StampedPose> ReadTum(const std::string& path);

// The pose nearest in time to `stamp` within `tolerance`, or nullptr.
const StampedPose* Nearest(const std::vector<StampedPose>& sorted, double stamp, double tolerance);

}  // namespace structloc::log_formats
