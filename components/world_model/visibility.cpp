// Visibility computation (see header).
#include "structloc/world_model/visibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace structloc::world_model {
namespace {

// Guard for the sample count of one wall; walls within WorldLimits need at
// most a few million samples at the default spacing.
constexpr double kMaxIntervals = 1e12;

bool InView(const geometry::Pose2D& sensor, const Eigen::Vector2d& p, const VisibilityOptions& o) {
  const Eigen::Vector2d d = p - sensor.Translation();
  const double range = d.norm();
  if (range < o.min_range_m || range > o.max_range_m) return false;
  if (o.field_of_view_rad >= 2.0 * geometry::kPi - 1e-9) return true;
  const double bearing = geometry::WrapAngle(std::atan2(d.y(), d.x()) - sensor.theta);
  return std::abs(bearing) <= 0.5 * o.field_of_view_rad;
}

}  // namespace

void ComputeVisibility(const WorldModel& world, const Scene& scene, const geometry::Pose2D& sensor,
                       const VisibilityOptions& o, Visibility& result) {
  result.walls.clear();
  result.corners.clear();
  result.cylinders.clear();
  const Eigen::Vector2d origin = sensor.Translation();
  const double cos_max_incidence = std::cos(o.max_incidence_rad);
  for (size_t i = 0; i < world.Walls().size(); ++i) {
    const auto& w = world.Walls()[i];
    const double length = w.Length();
    // Samples k = 0..intervals along the whole wall, counted in 64 bits.
    const double wanted = std::ceil(length / o.sample_spacing_m);
    const int64_t intervals =
        wanted >= 1.0 ? static_cast<int64_t>(std::min(wanted, kMaxIntervals)) : 1;
    // Only samples on the chord of the range circle can be in view: visit
    // those (one extra on each side against rounding), not the whole wall.
    const Eigen::Vector2d along_wall = (w.b - w.a) / length;
    const double along = (origin - w.a).dot(along_wall);
    const double off_line_sq = std::max(0.0, (origin - w.a).squaredNorm() - along * along);
    const double range_sq = o.max_range_m * o.max_range_m;
    if (off_line_sq > range_sq) continue;
    const double half_chord = std::sqrt(range_sq - off_line_sq);
    const double per_metre = static_cast<double>(intervals) / length;
    const auto first_k = static_cast<int64_t>(std::clamp(
        std::floor((along - half_chord) * per_metre) - 1.0, 0.0, static_cast<double>(intervals)));
    const auto last_k = static_cast<int64_t>(std::clamp(
        std::ceil((along + half_chord) * per_metre) + 1.0, 0.0, static_cast<double>(intervals)));
    const Eigen::Vector2d normal(std::cos(w.line.alpha), std::sin(w.line.alpha));
    VisibleWall vw;
    vw.index = static_cast<int>(i);
    bool any = false;
    for (int64_t k = first_k; k <= last_k; ++k) {
      const Eigen::Vector2d p =
          w.a + (w.b - w.a) * (static_cast<double>(k) / static_cast<double>(intervals));
      if (!InView(sensor, p, o)) continue;
      const Eigen::Vector2d ray = (p - origin).normalized();
      if (std::abs(ray.dot(normal)) < cos_max_incidence) continue;
      if (scene.Occluded(origin, p, o.occlusion_margin_m)) continue;
      if (!any) vw.first = p;
      vw.last = p;
      vw.visible_length_m += length / static_cast<double>(intervals);
      any = true;
    }
    if (any && vw.visible_length_m >= o.min_visible_length_m) result.walls.push_back(vw);
  }
  for (size_t i = 0; i < world.Corners().size(); ++i) {
    const Eigen::Vector2d p = world.Corners()[i].position;
    if (InView(sensor, p, o) && !scene.Occluded(origin, p, o.occlusion_margin_m)) {
      result.corners.push_back(static_cast<int>(i));
    }
  }
  for (size_t i = 0; i < world.Cylinders().size(); ++i) {
    const auto& c = world.Cylinders()[i];
    const Eigen::Vector2d to_centre = c.centre - origin;
    if (to_centre.norm() <= c.radius) continue;
    const Eigen::Vector2d near = c.centre - c.radius * to_centre.normalized();
    if (InView(sensor, near, o) && !scene.Occluded(origin, near, o.occlusion_margin_m)) {
      result.cylinders.push_back(static_cast<int>(i));
    }
  }
}

}  // namespace structloc::world_model
