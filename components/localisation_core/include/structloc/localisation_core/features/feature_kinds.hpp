// The list of feature kinds the localiser knows and the extractors a parameter
// file asks for. Each kind's own file describes it (name, options blocks,
// whether the file enables it, how its extractor is built); adding a kind adds
// one row to the list in feature_kinds.cpp.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "structloc/localisation_core/features/feature_extractor.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::localisation_core {

// How large an extractor's buffers must be so that updates never allocate.
struct ExtractorCapacity {
  size_t beams = 0;
  size_t wall_lines = 0;  // groups of collinear walls (expected walls at most)
  size_t corners = 0;
  size_t cylinders = 0;
};

// Everything the localiser needs to know about one feature kind.
struct FeatureKind {
  const char* name;  // as FeatureExtractor::Kind()
  // The kind's blocks in the parameter file, each option declared once.
  std::vector<config::OptionTable<LocaliserOptions>> (*sections)();
  bool (*enabled)(const LocaliserOptions&);
  std::unique_ptr<FeatureExtractor> (*make)(const LocaliserOptions&, const ExtractorCapacity&);
};

// The known kinds, in the order their extractors run.
std::vector<FeatureKind> FeatureKinds();

// The extractors enabled in `options`, in the order of FeatureKinds() (walls
// first: later kinds may read the walls' measurements).
std::vector<std::unique_ptr<FeatureExtractor>> MakeFeatureExtractors(
    const LocaliserOptions& options, const ExtractorCapacity& capacity);

}  // namespace structloc::localisation_core
