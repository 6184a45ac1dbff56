// The table of feature kinds (see header).
#include "feature_kinds.hpp"

#include "corner_extractor.hpp"
#include "cylinder_extractor.hpp"
#include "wall_extractor.hpp"

namespace structloc::localisation {
namespace {

struct FeatureKind {
  bool (*enabled)(const LocaliserOptions&);
  std::unique_ptr<FeatureExtractor> (*make)(const LocaliserOptions&, const ExtractorCapacity&);
};

const FeatureKind kKinds[] = {
    {[](const LocaliserOptions&) { return true; },
     [](const LocaliserOptions& o,
        const ExtractorCapacity& c) -> std::unique_ptr<FeatureExtractor> {
       return std::make_unique<WallExtractor>(o, c.beams, c.wall_lines);
     }},
    {[](const LocaliserOptions& o) { return o.use_corners; },
     [](const LocaliserOptions& o,
        const ExtractorCapacity& c) -> std::unique_ptr<FeatureExtractor> {
       return std::make_unique<CornerExtractor>(o.corners, c.corners);
     }},
    {[](const LocaliserOptions& o) { return o.use_cylinders; },
     [](const LocaliserOptions& o,
        const ExtractorCapacity& c) -> std::unique_ptr<FeatureExtractor> {
       return std::make_unique<CylinderExtractor>(o.cylinders, c.beams, c.cylinders);
     }},
};

}  // namespace

std::vector<std::unique_ptr<FeatureExtractor>> MakeFeatureExtractors(
    const LocaliserOptions& options, const ExtractorCapacity& capacity) {
  std::vector<std::unique_ptr<FeatureExtractor>> extractors;
  for (const auto& kind : kKinds) {
    if (kind.enabled(options)) extractors.push_back(kind.make(options, capacity));
  }
  return extractors;
}

}  // namespace structloc::localisation
