// Kuemmerle et al. 2009's relation files ("On measuring the accuracy of SLAM
// algorithms"): hand-verified relative poses between pairs of scans,
// "t1 t2 x y z roll pitch yaw" per line, the robot pose at t2 in the robot
// frame at t1; the 2-D sets have z = roll = pitch = 0. DDS-free.
#pragma once

#include <string>
#include <vector>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::log_formats {

struct Relation {
  double t1 = 0.0;
  double t2 = 0.0;
  geometry::Pose2D relative;  // the pose at t2 in the frame of the pose at t1
};

// Throws std::runtime_error naming the file and line of anything that is not
// eight finite numbers (blank lines and '#' comments are skipped), or when
// the file cannot be read or holds no relation.
std::vector<Relation> ReadRelations(const std::string& path);

}  // namespace structloc::log_formats
