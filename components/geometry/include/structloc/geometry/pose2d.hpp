// Planar poses and angles in ROS conventions (metres, radians, right-handed,
// angles wrapped to (-pi, pi]). Header-only, used by every core library.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace structloc::geometry {

constexpr double kPi = 3.14159265358979323846;
constexpr double kHalfPi = kPi / 2;

// Wraps any finite angle to (-pi, pi].
inline double WrapAngle(double a) {
  if (a > -kPi && a <= kPi) return a;
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a <= 0.0) a += 2.0 * kPi;
  return a - kPi;
}

// Wraps an angle known to lie in (-3pi, 3pi] with at most one correction (hot loops).
inline double WrapAngleNear(double a) {
  if (a > kPi) return a - 2.0 * kPi;
  if (a <= -kPi) return a + 2.0 * kPi;
  return a;
}

struct Pose2D {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  Eigen::Vector2d Translation() const { return {x, y}; }
  // Maps a point from this pose's frame into the parent frame.
  Eigen::Vector2d Apply(const Eigen::Vector2d& p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
  // Maps a point from the parent frame into this pose's frame.
  Eigen::Vector2d ApplyInverse(const Eigen::Vector2d& p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    const double dx = p.x() - x, dy = p.y() - y;
    return {c * dx + s * dy, -s * dx + c * dy};
  }
};

// a * b: the pose b (given in frame a) expressed in a's parent frame.
inline Pose2D Compose(const Pose2D& a, const Pose2D& b) {
  const Eigen::Vector2d t = a.Apply(b.Translation());
  return {t.x(), t.y(), WrapAngle(a.theta + b.theta)};
}

inline Pose2D Inverse(const Pose2D& a) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  return {-(c * a.x + s * a.y), -(-s * a.x + c * a.y), WrapAngle(-a.theta)};
}

// a^-1 * b: b relative to a.
inline Pose2D Between(const Pose2D& a, const Pose2D& b) {
  return Compose(Inverse(a), b);
}

// Linear interpolation in x, y and (shortest-way) theta; f in [0, 1].
inline Pose2D Interpolate(const Pose2D& a, const Pose2D& b, double f) {
  return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y),
          WrapAngle(a.theta + f * WrapAngle(b.theta - a.theta))};
}

inline bool IsFinite(const Pose2D& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

}  // namespace structloc::geometry
