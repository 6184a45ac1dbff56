// Feature kind "cylinders" (see header): the extractor and the kind's options block.
#include "structloc/localisation_core/features/cylinders/cylinder_extractor.hpp"

#include "structloc/localisation_core/association/point_gate.hpp"

namespace structloc::localisation_core {
namespace {

using config::Range;

std::vector<LocaliserOptionTable> CylinderSections() {
  using K = CylinderKindOptions;
  using C = CylinderOptions;
  config::OptionTable<K> t("cylinders",
                           "feature kind cylinders, thesis 3.5.6 EQ 36-40: circle fits");
  t.Flag("enabled", &K::enabled, "extract and use cylinders");
  t.Number("candidate_gate_m", &K::extraction, &C::candidate_gate_m, Range::Positive(), "m",
           "window centroid to expected surface");
  t.Number("radius_tolerance_m", &K::extraction, &C::radius_tolerance_m, Range::Positive(), "m",
           "|fitted radius - model radius|");
  t.Number("min_quality", &K::extraction, &C::min_quality, Range::NonNegative(), "1/m^4",
           "EQ 40 threshold on Q = 1 / sum(residual^2)");
  t.Number("gate_m", &K::extraction, &C::gate_m, Range::Positive(), "m",
           "fitted centre to expected centre");
  t.Number("min_cluster_size", &K::extraction, &C::min_cluster_size, Range::AtLeast(1), "",
           "minimum number of circle fits in a cluster");
  t.Number("min_point_sigma_m", &K::extraction, &C::min_point_sigma_m, Range::Positive(), "m",
           "floor of the per-point noise for the covariance");
  t.Number("map_sigma_m", &K::extraction, &C::map_sigma_m, Range::NonNegative(), "m",
           "the map's error of a pillar centre, 1 sigma (0: exact map)");
  t.Number("gate_chi2", &K::extraction, &C::gate_chi2, Range::NonNegative(), "",
           "Mahalanobis gate (2 dof) under the prior's, the fit's and the map's covariance (0: "
           "fixed gate only)");
  return {LocaliserOptionTable::Of(
      t, [](auto& o) -> auto& { return o.kinds.template Get<K>(); })};
}

}  // namespace

FeatureKind CylinderKind() {
  return {"cylinders", CylinderSections,
          [](const LocaliserOptions& o) { return o.kinds.Get<CylinderKindOptions>().enabled; },
          [](const LocaliserOptions& o, const world_model::WorldModel& map, size_t max_beams) {
            return std::unique_ptr<FeatureExtractor>(std::make_unique<CylinderExtractor>(
                o.kinds.Get<CylinderKindOptions>().extraction, max_beams, map.Cylinders().size()));
          }};
}

CylinderExtractor::CylinderExtractor(const CylinderOptions& options, size_t max_beams,
                                     size_t cylinders)
    : options_(options) {
  expected_.reserve(cylinders);
  work_.Reserve(max_beams, cylinders);
  clusters_.reserve(cylinders);
}

int CylinderExtractor::TakeSlots(const world_model::WorldModel& map, int first_slot) {
  first_slot_ = first_slot;
  return static_cast<int>(map.Cylinders().size());
}

void CylinderExtractor::Expect(const ExpectationInput& in) {
  expected_.clear();
  for (int i : in.visibility->cylinders) {
    const auto& c = in.map->Cylinders()[static_cast<size_t>(i)];
    expected_.push_back(
        ExpectPoint(i, c.id, c.centre, c.radius, first_slot_, in.sensor_prior, *in.map_errors));
  }
}

void CylinderExtractor::Extract(const ExtractionInput& in, Measurements& all,
                                std::vector<FeatureMatch>& matches) {
  ExtractCylinders(*in.windows, *in.points, expected_, options_, in.window_points, work_,
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
    m.bisection = BisectionTerm::kDistance;  // EQ 43
    FeatureMatch match;
    match.model_id = e.model_id;
    match.slot = e.slot;
    match.members = c.members;
    match.x_m = m.sensor.x();
    match.y_m = m.sensor.y();
    match.radius_m = e.radius;
    match.row = static_cast<int>(all.points.size());
    all.points.push_back(m);
    matches.push_back(match);
  }
}

}  // namespace structloc::localisation_core
