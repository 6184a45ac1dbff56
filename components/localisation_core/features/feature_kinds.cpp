// The list of feature kinds (see header).
#include "structloc/localisation_core/features/feature_kinds.hpp"

#include "structloc/localisation_core/features/corners/corner_extractor.hpp"
#include "structloc/localisation_core/features/cylinders/cylinder_extractor.hpp"
#include "structloc/localisation_core/features/walls/wall_extractor.hpp"

namespace structloc::localisation_core {

std::vector<FeatureKind> FeatureKinds() {
  // Walls first: the corners' redundancy rule reads the walls' measurements.
  return {WallKind(), CornerKind(), CylinderKind()};
}

std::vector<std::unique_ptr<FeatureExtractor>> MakeFeatureExtractors(
    const LocaliserOptions& options, const world_model::WorldModel& map, size_t max_beams) {
  std::vector<std::unique_ptr<FeatureExtractor>> extractors;
  for (const auto& kind : FeatureKinds()) {
    if (kind.enabled(options)) extractors.push_back(kind.make(options, map, max_beams));
  }
  return extractors;
}

}  // namespace structloc::localisation_core
