// Feature kind "walls" (see header).
#include "wall_extractor.hpp"

namespace structloc::localisation {

WallExtractor::WallExtractor(const LocaliserOptions& options, size_t max_beams, size_t wall_lines)
    : strategy_(options.wall_strategy),
      options_(options.walls),
      kohonen_(options.kohonen),
      rng_(options.kohonen_seed) {
  assignment_.reserve(max_beams);
  work_.Reserve(max_beams, wall_lines);
  clusters_.reserve(wall_lines);
}

void WallExtractor::Extract(const ExtractionInput& in, Measurements& all,
                            std::vector<FeatureMatch>& matches) {
  const auto& expected = *in.expected;
  if (strategy_ == WallStrategy::kKohonen) {
    AssignWindowsByKohonen(*in.windows, expected, options_, kohonen_, rng_, assignment_);
  } else {
    AssignWindowsByExpectation(*in.windows, expected, in.sensor_prior, options_, assignment_);
  }
  BuildWallClusters(*in.windows, assignment_, *in.points, in.window_points, expected, options_,
                    work_, clusters_);
  for (const auto& c : clusters_) {
    const auto& e = expected.walls[static_cast<size_t>(c.expected_index)];
    WallMeasurement m;
    m.r = in.thesis_values ? c.mean_r : c.refined_r;
    m.alpha = in.thesis_values ? c.mean_alpha : c.refined_alpha;
    m.covariance = c.covariance;
    m.world_r = e.world.r;
    m.world_alpha = e.world.alpha;
    FeatureMatch match;
    match.model_id = e.model_id;
    match.members = c.members;
    match.r_m = m.r;
    match.alpha_rad = m.alpha;
    match.row = static_cast<int>(all.lines.size());
    all.lines.push_back(m);
    matches.push_back(match);
  }
}

}  // namespace structloc::localisation
