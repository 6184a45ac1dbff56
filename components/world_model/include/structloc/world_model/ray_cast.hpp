// Ray casting against segments and circles: the simulator's laser, the test
// helpers' synthetic scans, and the visibility check all use this one code.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "structloc/world_model/world_model.hpp"

namespace structloc::world_model {

struct Segment {
  Eigen::Vector2d a{0, 0};
  Eigen::Vector2d b{0, 0};
};

struct Circle {
  Eigen::Vector2d centre{0, 0};
  double radius = 0.0;
};

// Everything a laser beam can hit.
struct Scene {
  std::vector<Segment> segments;
  std::vector<Circle> circles;

  static Scene FromWorld(const WorldModel& world);
  void Add(const Scene& other);

  // Distance along the unit direction to the nearest surface, or +infinity
  // when nothing is hit within max_range.
  double Cast(const Eigen::Vector2d& origin, const Eigen::Vector2d& unit_direction,
              double max_range) const;
  // True when a surface lies between origin and target, more than `margin`
  // before the target.
  bool Occluded(const Eigen::Vector2d& origin, const Eigen::Vector2d& target, double margin) const;
};

// Intersection distances of one ray with one shape; +infinity when missed.
double RaySegment(const Eigen::Vector2d& origin, const Eigen::Vector2d& unit_direction,
                  const Segment& segment);
double RayCircle(const Eigen::Vector2d& origin, const Eigen::Vector2d& unit_direction,
                 const Circle& circle);

}  // namespace structloc::world_model
