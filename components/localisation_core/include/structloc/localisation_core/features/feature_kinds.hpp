// The list of feature kinds the localiser knows and the extractors a parameter
// file asks for. Each kind's own folder describes it (name, its options type
// and blocks, whether the file enables it, how its extractor is built and
// sized from the map); adding a kind adds one row to the list in
// feature_kinds.cpp and no member to any shared struct.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "structloc/localisation_core/features/feature_extractor.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::localisation_core {

// Everything the localiser needs to know about one feature kind.
struct FeatureKind {
  const char* name;  // as FeatureExtractor::Kind()
  // The kind's blocks in the parameter file, each option declared once on
  // the kind's own options type (LocaliserOptionTable::Of).
  std::vector<config::OptionTable<LocaliserOptions>> (*sections)();
  bool (*enabled)(const LocaliserOptions&);
  // The extractor, its buffers sized for scans of up to `max_beams` beams and
  // for the features of `map`, so that updates never allocate.
  std::unique_ptr<FeatureExtractor> (*make)(const LocaliserOptions&,
                                            const world_model::WorldModel& map, size_t max_beams);
};

// The known kinds, in the order their extractors run.
std::vector<FeatureKind> FeatureKinds();

// The extractors enabled in `options`, in the order of FeatureKinds() (walls
// first: later kinds may read the walls' measurements).
std::vector<std::unique_ptr<FeatureExtractor>> MakeFeatureExtractors(
    const LocaliserOptions& options, const world_model::WorldModel& map, size_t max_beams);

}  // namespace structloc::localisation_core
