// Feature kind "cylinders" (thesis 3.5.6, EQ 36-40): sliding circle fits
// clustered around expected pillar centres; one point measurement per matched
// pillar (the thesis solver's EQ 43 treats it as a circle, not a point).
#pragma once

#include "structloc/localisation_core/features/cylinders/cylinder_extraction.hpp"
#include "structloc/localisation_core/features/feature_extractor.hpp"
#include "structloc/localisation_core/features/feature_kinds.hpp"

namespace structloc::localisation_core {

// The kind's options: its block <cylinders> of the parameter file.
struct CylinderKindOptions {
  bool enabled = true;  // extract and use cylinders
  CylinderOptions extraction;
};

class CylinderExtractor : public FeatureExtractor {
 public:
  // Buffers for `max_beams` beams and `cylinders` expected pillars.
  CylinderExtractor(const CylinderOptions& options, size_t max_beams, size_t cylinders);
  const char* Kind() const override { return "cylinders"; }
  FeatureShape Shape() const override { return FeatureShape::kPoint; }
  int TakeSlots(const world_model::WorldModel& map, int first_slot) override;
  void Expect(const ExpectationInput& in) override;
  int Expected() const override { return static_cast<int>(expected_.size()); }
  void Extract(const ExtractionInput& in, Measurements& all,
               std::vector<FeatureMatch>& matches) override;

 private:
  CylinderOptions options_;
  int first_slot_ = -1;  // none until TakeSlots: no map-error memory
  std::vector<ExpectedPoint> expected_;
  CylinderWork work_;
  std::vector<PointCluster> clusters_;
};

// The kind "cylinders": its options blocks, when it is enabled, how it is built.
FeatureKind CylinderKind();

}  // namespace structloc::localisation_core
