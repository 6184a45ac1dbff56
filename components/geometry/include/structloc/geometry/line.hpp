// Lines in Hessian normal form (r, alpha): x cos(alpha) + y sin(alpha) = r,
// r >= 0, alpha in (-pi, pi] (thesis 3.5.1, EQ 7), and their transformation
// between frames (EQ 23, 24).
#pragma once

#include <Eigen/Core>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::geometry {

struct Line {
  double r = 0.0;
  double alpha = 0.0;
};

// Brings r to >= 0 by flipping the normal, and wraps alpha.
inline Line Normalised(double r, double alpha) {
  if (r < 0.0) return {-r, WrapAngle(alpha + kPi)};
  return {r, WrapAngle(alpha)};
}

// The line through two distinct points.
inline Line LineThrough(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = (b - a).normalized();
  const double alpha = std::atan2(d.x(), -d.y());  // normal = d rotated by -90 deg
  return Normalised(a.x() * std::cos(alpha) + a.y() * std::sin(alpha), alpha);
}

// A world line seen from a frame at `pose` (EQ 23, 24), unnormalised: r may be
// negative (the frame is on the other side), alpha = alpha_W - theta.
inline Line LineInFrameSigned(const Line& world, const Pose2D& pose) {
  return {world.r - (pose.x * std::cos(world.alpha) + pose.y * std::sin(world.alpha)),
          WrapAngle(world.alpha - pose.theta)};
}

inline Line LineInFrame(const Line& world, const Pose2D& pose) {
  const Line l = LineInFrameSigned(world, pose);
  return Normalised(l.r, l.alpha);
}

}  // namespace structloc::geometry
