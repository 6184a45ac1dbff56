// Feature kind "cylinders" (see header).
#include "cylinder_extractor.hpp"

namespace structloc::localisation {

CylinderExtractor::CylinderExtractor(const CylinderOptions& options, size_t max_beams,
                                     size_t cylinders)
    : options_(options) {
  work_.Reserve(max_beams, cylinders);
  clusters_.reserve(cylinders);
}

void CylinderExtractor::Extract(const ExtractionInput& in, Measurements& all,
                                std::vector<FeatureMatch>& matches) {
  const auto& expected = *in.expected;
  ExtractCylinders(*in.windows, *in.points, expected, options_, in.window_points, work_, clusters_);
  for (const auto& c : clusters_) {
    const auto& e = expected.cylinders[static_cast<size_t>(c.expected_index)];
    PointMeasurement m;
    m.sensor = in.thesis_values ? c.mean : c.refined;
    m.covariance = c.covariance;
    m.world = e.world;
    m.cylinder = true;
    FeatureMatch match;
    match.model_id = e.model_id;
    match.members = c.members;
    match.x_m = m.sensor.x();
    match.y_m = m.sensor.y();
    match.radius_m = e.radius;
    match.row = static_cast<int>(all.points.size());
    all.points.push_back(m);
    matches.push_back(match);
  }
}

}  // namespace structloc::localisation
