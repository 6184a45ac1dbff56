// Feature kind "corners" (thesis 3.5.4, EQ 31): crossings of window lines
// clustered around expected corners; one point measurement per matched corner,
// left out of the weighted solve when two matched walls already fix it.
#pragma once

#include "structloc/localisation_core/features/corners/corner_extraction.hpp"
#include "structloc/localisation_core/features/feature_extractor.hpp"
#include "structloc/localisation_core/features/feature_kinds.hpp"

namespace structloc::localisation_core {

// The kind's options: its block <corners> of the parameter file.
struct CornerKindOptions {
  bool enabled = true;  // extract and use corners
  CornerOptions extraction;
};

class CornerExtractor : public FeatureExtractor {
 public:
  // Buffers for `corners` expected corners.
  CornerExtractor(const CornerOptions& options, size_t max_beams, size_t corners);
  const char* Kind() const override { return "corners"; }
  FeatureShape Shape() const override { return FeatureShape::kPoint; }
  int TakeSlots(const world_model::WorldModel& map, int first_slot) override;
  void Expect(const ExpectationInput& in) override;
  int Expected() const override { return static_cast<int>(expected_.size()); }
  void Extract(const ExtractionInput& in, Measurements& all,
               std::vector<FeatureMatch>& matches) override;

 private:
  // A corner where two matched, non-parallel walls meet adds nothing they do
  // not already say; counting it twice would make the covariance lie.
  bool RedundantWithWalls(const Eigen::Vector2d& corner,
                          const std::vector<WallMeasurement>& walls) const;

  CornerOptions options_;
  int first_slot_ = -1;  // none until TakeSlots: no map-error memory
  std::vector<ExpectedPoint> expected_;
  CornerWork work_;
  std::vector<PointCluster> clusters_;
};

// The kind "corners": its options blocks, when it is enabled, how it is built.
FeatureKind CornerKind();

}  // namespace structloc::localisation_core
