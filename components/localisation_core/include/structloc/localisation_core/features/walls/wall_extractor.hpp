// Feature kind "walls" (thesis 3.5.3): window lines clustered per expected wall
// by the expectation gates or the thesis' Kohonen map; one line measurement per
// matched wall.
#pragma once

#include <cstdint>
#include <random>

#include "structloc/localisation_core/features/feature_extractor.hpp"
#include "structloc/localisation_core/features/feature_kinds.hpp"
#include "structloc/localisation_core/features/walls/kohonen_clustering.hpp"
#include "structloc/localisation_core/features/walls/wall_clustering.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"

namespace structloc::localisation_core {

enum class WallStrategy { kExpectation, kKohonen };

// The kind's options: its blocks <walls> and <kohonen> of the parameter file.
struct WallKindOptions {
  // Bounds a typo's cost: 50 x the thesis' 2000 training steps.
  static constexpr int kMaxKohonenIterations = 100000;
  WallStrategy strategy = WallStrategy::kExpectation;
  WallClusterOptions clusters;
  KohonenOptions kohonen;
  uint32_t kohonen_seed = 1;  // seeds the Kohonen strategy's generator
};

class WallExtractor : public FeatureExtractor {
 public:
  // Buffers for `max_beams` beams and `wall_lines` expected walls.
  WallExtractor(const WallKindOptions& options, size_t max_beams, size_t wall_lines);
  const char* Kind() const override { return "walls"; }
  FeatureShape Shape() const override { return FeatureShape::kLine; }
  int TakeSlots(const world_model::WorldModel&, int) override { return 0; }
  void Expect(const ExpectationInput& in) override {
    expected_ = static_cast<int>(in.walls->walls.size());
  }
  int Expected() const override { return expected_; }
  void Extract(const ExtractionInput& in, Measurements& all,
               std::vector<FeatureMatch>& matches) override;

 private:
  int expected_ = 0;
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
