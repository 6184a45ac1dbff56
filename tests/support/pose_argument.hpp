// Test helper: a pose written as the components' --initial-pose takes it,
// for the tests that start them.
#pragma once

#include <string>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::testing {

// "X Y THETA".
inline std::string PoseArgument(const geometry::Pose2D& p) {
  return std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.theta);
}

}  // namespace structloc::testing
