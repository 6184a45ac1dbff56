// Feature kind "corners" (see header): the extractor and the kind's options block.
#include "structloc/localisation_core/features/corners/corner_extractor.hpp"

#include "structloc/localisation_core/association/point_gate.hpp"

#include <cmath>
#include <optional>

namespace structloc::localisation_core {
namespace {

using config::Range;

std::vector<LocaliserOptionTable> CornerSections() {
  using K = CornerKindOptions;
  using C = CornerOptions;
  config::OptionTable<K> t("corners",
                           "feature kind corners, thesis 3.5.4 EQ 31: window-line crossings");
  t.Flag("enabled", &K::enabled, "extract and use corners");
  t.Number("next_windows", &K::extraction, &C::next_windows, Range::AtLeast(1), "",
           "k: windows after window i intersected with it");
  t.Number("angle_tolerance_rad", &K::extraction, &C::angle_tolerance_rad,
           Range::Open(0, geometry::kHalfPi), "rad", "lines must meet at pi/2 within this");
  t.Number("gate_m", &K::extraction, &C::gate_m, Range::Positive(), "m",
           "distance gate around an expected corner");
  t.Number("min_cluster_size", &K::extraction, &C::min_cluster_size, Range::AtLeast(1), "",
           "minimum number of crossings in a cluster");
  t.Number("min_point_sigma_m", &K::extraction, &C::min_point_sigma_m, Range::Positive(), "m",
           "floor of a corner's standard deviation");
  t.Number("redundant_wall_distance_m", &K::extraction, &C::redundant_wall_distance_m,
           Range::Positive(), "m", "a matched wall passes through a corner within this");
  t.Number("redundant_min_sin", &K::extraction, &C::redundant_min_sin, Range::Closed(0, 1), "",
           "two such walls at an angle with a larger sine make the corner redundant");
  t.Number("map_sigma_m", &K::extraction, &C::map_sigma_m, Range::NonNegative(), "m",
           "the map's error of a corner, 1 sigma (0: exact map)");
  t.Number("gate_chi2", &K::extraction, &C::gate_chi2, Range::NonNegative(), "",
           "Mahalanobis gate (2 dof) under the prior's, the fit's and the map's covariance (0: "
           "fixed gate only)");
  return {LocaliserOptionTable::Of(
      t, [](auto& o) -> auto& { return o.kinds.template Get<K>(); })};
}

}  // namespace

FeatureKind CornerKind() {
  return {"corners", CornerSections,
          [](const LocaliserOptions& o) { return o.kinds.Get<CornerKindOptions>().enabled; },
          [](const LocaliserOptions& o, const world_model::WorldModel& map, size_t max_beams) {
            return std::unique_ptr<FeatureExtractor>(std::make_unique<CornerExtractor>(
                o.kinds.Get<CornerKindOptions>().extraction, max_beams, map.Corners().size()));
          }};
}

CornerExtractor::CornerExtractor(const CornerOptions& options, size_t max_beams, size_t corners)
    : options_(options) {
  expected_.reserve(corners);
  work_.Reserve(max_beams, corners);
  clusters_.reserve(corners);
}

int CornerExtractor::TakeSlots(const world_model::WorldModel& map, int first_slot) {
  first_slot_ = first_slot;
  return static_cast<int>(map.Corners().size());
}

void CornerExtractor::Expect(const ExpectationInput& in) {
  expected_.clear();
  for (int i : in.visibility->corners) {
    const auto& c = in.map->Corners()[static_cast<size_t>(i)];
    expected_.push_back(
        ExpectPoint(i, c.id, c.position, 0.0, first_slot_, in.sensor_prior, *in.map_errors));
  }
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
  ExtractCorners(*in.windows, in.points->wraps, expected_, options_, in.window_points, work_,
                 clusters_);
  for (const auto& c : clusters_) {
    const auto& e = expected_[static_cast<size_t>(c.expected_index)];
    PointMeasurement m;
    m.sensor = in.thesis_values ? c.mean : c.refined;
    m.covariance = c.covariance;
    m.world = e.world;
    if (!GatePoint(m.sensor, m.covariance, m.world, in.sensor_prior, in.sensor_prior_covariance,
                   options_.map_sigma_m, options_.gate_chi2, e.map_error_scale)) {
      continue;
    }
    m.use_in_weighted = !RedundantWithWalls(e.world, all.lines);
    FeatureMatch match;
    match.model_id = e.model_id;
    match.slot = e.slot;
    match.members = c.members;
    match.x_m = m.sensor.x();
    match.y_m = m.sensor.y();
    match.row = static_cast<int>(all.points.size());
    all.points.push_back(m);
    matches.push_back(match);
  }
}

}  // namespace structloc::localisation_core
