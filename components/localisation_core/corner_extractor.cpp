// Feature kind "corners" (see header).
#include "corner_extractor.hpp"

#include <cmath>
#include <optional>

namespace structloc::localisation {

CornerExtractor::CornerExtractor(const CornerOptions& options, size_t corners) : options_(options) {
  work_.reserve(corners);
  clusters_.reserve(corners);
}

bool CornerExtractor::RedundantWithWalls(const Eigen::Vector2d& corner,
                                         const std::vector<WallMeasurement>& walls) const {
  std::optional<double> first_alpha;  // of the first matched wall through the corner
  for (const auto& w : walls) {
    const bool through_corner =
        std::abs(corner.x() * std::cos(w.world_alpha) + corner.y() * std::sin(w.world_alpha) -
                 w.world_r) < options_.redundant_wall_distance_m;
    if (!through_corner) continue;
    if (!first_alpha) {
      first_alpha = w.world_alpha;
    } else if (std::abs(std::sin(w.world_alpha - *first_alpha)) > options_.redundant_min_sin) {
      return true;
    }
  }
  return false;
}

void CornerExtractor::Extract(const ExtractionInput& in, Measurements& all,
                              std::vector<FeatureMatch>& matches) {
  const auto& expected = *in.expected;
  ExtractCorners(*in.windows, in.points->wraps, expected, options_, in.window_points, work_,
                 clusters_);
  for (const auto& c : clusters_) {
    const auto& e = expected.corners[static_cast<size_t>(c.expected_index)];
    PointMeasurement m;
    m.sensor = in.thesis_values ? c.mean : c.refined;
    m.covariance = c.covariance;
    m.world = e.world;
    m.use_in_weighted = !RedundantWithWalls(e.world, all.lines);
    FeatureMatch match;
    match.model_id = e.model_id;
    match.members = c.members;
    match.x_m = m.sensor.x();
    match.y_m = m.sensor.y();
    match.row = static_cast<int>(all.points.size());
    all.points.push_back(m);
    matches.push_back(match);
  }
}

}  // namespace structloc::localisation
