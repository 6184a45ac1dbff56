// Feature kind "walls" (thesis 3.5.3): window lines clustered per expected wall
// by the expectation gates or the thesis' Kohonen map; one line measurement per
// matched wall.
#pragma once

#include <random>

#include "structloc/localisation_core/features/feature_extractor.hpp"
#include "structloc/localisation_core/features/feature_kinds.hpp"
#include "structloc/localisation_core/features/walls/kohonen_clustering.hpp"
#include "structloc/localisation_core/features/walls/wall_clustering.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"

namespace structloc::localisation_core {

class WallExtractor : public FeatureExtractor {
 public:
  // Buffers for `max_beams` beams and `wall_lines` expected walls.
  WallExtractor(const LocaliserOptions& options, size_t max_beams, size_t wall_lines);
  const char* Kind() const override { return "walls"; }
  FeatureShape Shape() const override { return FeatureShape::kLine; }
  int Expected(const ExpectedFeatures& expected) const override {
    return static_cast<int>(expected.walls.size());
  }
  void Extract(const ExtractionInput& in, Measurements& all,
               std::vector<FeatureMatch>& matches) override;

 private:
  WallStrategy strategy_;
  WallClusterOptions options_;
  KohonenOptions kohonen_;
  std::mt19937 rng_;  // the Kohonen strategy's, seeded from the parameter file
  std::vector<int> assignment_;
  WallClusterWork work_;
  std::vector<WallCluster> clusters_;
};

// The kind "walls": its options blocks, when it is enabled, how it is built.
FeatureKind WallKind();

}  // namespace structloc::localisation_core
