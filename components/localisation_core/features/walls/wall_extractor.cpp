// Feature kind "walls" (see header): the extractor and the kind's options blocks.
#include "structloc/localisation_core/features/walls/wall_extractor.hpp"

namespace structloc::localisation_core {
namespace {

using config::Range;

std::vector<LocaliserOptionTable> WallSections() {
  using W = WallKindOptions;
  using C = WallClusterOptions;
  config::OptionTable<W> t("walls",
                           "feature kind walls, thesis 3.5.3: window lines clustered per wall");
  t.Choice("strategy", &W::strategy,
           {{"expectation", WallStrategy::kExpectation}, {"kohonen", WallStrategy::kKohonen}},
           "nearest expected wall within the gates, or the thesis' Kohonen map (see <kohonen>)");
  t.Number("gate_r_m", &W::clusters, &C::gate_r_m, Range::Positive(), "m",
           "Table 6: size of cluster (r)");
  t.Number("gate_alpha_rad", &W::clusters, &C::gate_alpha_rad, Range::Open(0, geometry::kHalfPi),
           "rad", "Table 6: size of cluster (alpha)");
  t.Number("min_cluster_size", &W::clusters, &C::min_cluster_size, Range::AtLeast(1), "",
           "Table 6: minimum number of window lines in a cluster");
  t.Number("extent_margin_m", &W::clusters, &C::extent_margin_m, Range::Any(), "m",
           "a window must lie within the visible part of one map wall plus this (<= 0 disables "
           "the check)");
  t.Number("min_point_sigma_m", &W::clusters, &C::min_point_sigma_m, Range::Positive(), "m",
           "floor of the per-point noise used for covariances");
  t.Number("map_sigma_r_m", &W::clusters, &C::map_sigma_r_m, Range::NonNegative(), "m",
           "the map's error: a wall's offset at its centre, 1 sigma (0: exact map)");
  t.Number("map_sigma_alpha_rad", &W::clusters, &C::map_sigma_alpha_rad, Range::NonNegative(),
           "rad", "the map's error: a wall's angle, 1 sigma (0: exact map)");
  t.Number("gate_chi2", &W::clusters, &C::gate_chi2, Range::NonNegative(), "",
           "Mahalanobis gate (2 dof) of a pairing under the prior's, the fit's and the map's "
           "covariance; pairings inside two walls' gates are dropped (0: fixed gates only)");
  config::OptionTable<W> k("kohonen", "walls strategy kohonen, thesis 3.5.3 EQ 21-22");
  k.Number("iterations", &W::kohonen, &KohonenOptions::iterations,
           Range::Closed(1, W::kMaxKohonenIterations), "", "training steps per scan");
  k.Number("initial_learning_rate", &W::kohonen, &KohonenOptions::initial_learning_rate,
           Range::LeftOpen(0, 1), "", "eta(0), decreasing linearly to 0");
  k.Number("initial_neighbourhood", &W::kohonen, &KohonenOptions::initial_neighbourhood,
           Range::NonNegative(), "", "sigma(0) in neuron-index units, shrinking to 0");
  k.Number("seed", &W::kohonen_seed, Range::Any(), "", "seeds the Kohonen strategy's generator");
  const auto part = [](auto& o) -> auto& {
    return o.kinds.template Get<W>();
  };
  return {LocaliserOptionTable::Of(t, part), LocaliserOptionTable::Of(k, part)};
}

}  // namespace

FeatureKind WallKind() {
  return {"walls", WallSections, [](const LocaliserOptions&) { return true; },
          [](const LocaliserOptions& o, const world_model::WorldModel& map, size_t max_beams) {
            // The walls bound the groups of collinear walls from above.
            return std::unique_ptr<FeatureExtractor>(std::make_unique<WallExtractor>(
                o.kinds.Get<WallKindOptions>(), max_beams, map.Walls().size()));
          }};
}

WallExtractor::WallExtractor(const WallKindOptions& options, size_t max_beams, size_t wall_lines)
    : strategy_(options.strategy),
      options_(options.clusters),
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
    AssignWindowsByExpectation(*in.windows, expected, in.sensor_prior, in.sensor_prior_covariance,
                               options_, work_, assignment_);
  }
  BuildWallClusters(*in.windows, assignment_, *in.points, in.window_points, expected, options_,
                    in.thesis_values ? ClusterMeans::kCompute : ClusterMeans::kSkip, work_,
                    clusters_);
  GateWallClusters(expected, in.sensor_prior, in.sensor_prior_covariance, options_, clusters_);
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
    match.slot = e.slot;
    match.members = c.members;
    match.r_m = m.r;
    match.alpha_rad = m.alpha;
    match.row = static_cast<int>(all.lines.size());
    all.lines.push_back(m);
    matches.push_back(match);
  }
}

}  // namespace structloc::localisation_core
