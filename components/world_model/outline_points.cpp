// The map's outline sampled as points (see header).
#include "structloc/world_model/outline_points.hpp"

#include <algorithm>
#include <cmath>

namespace structloc::world_model {

std::vector<Eigen::Vector2d> OutlinePoints(const WorldModel& world, double step_m,
                                           int min_pillar_points) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& wall : world.Walls()) {
    const int n = std::max(1, static_cast<int>(std::ceil(wall.Length() / step_m)));
    for (int i = 0; i <= n; ++i) points.push_back(wall.a + (wall.b - wall.a) * (double(i) / n));
  }
  for (const auto& pillar : world.Cylinders()) {
    const int n = std::max(min_pillar_points,
                           static_cast<int>(std::ceil(2 * geometry::kPi * pillar.radius / step_m)));
    for (int i = 0; i < n; ++i) {
      const double a = 2 * geometry::kPi * i / n;
      points.push_back(pillar.centre + pillar.radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
  }
  return points;
}

}  // namespace structloc::world_model
