// Test helper: the first pose of a TUM file (x, y and the yaw of its
// quaternion), where replays of a recording start from its truth.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::testing {

inline geometry::Pose2D FirstTumPose(const std::string& tum) {
  std::ifstream in(tum);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double t, x, y, z, qx, qy, qz, qw;
    fields >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
    return {x, y, 2.0 * std::atan2(qz, qw)};
  }
  ADD_FAILURE() << tum << " has no pose";
  return {};
}

}  // namespace structloc::testing
