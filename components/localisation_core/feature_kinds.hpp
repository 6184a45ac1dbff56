// The list of feature kinds the localiser knows and the extractors a parameter
// file asks for: each kind with its section name, whether the file enables it,
// and how its extractor is built. Adding a kind adds one row here.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "feature_extractor.hpp"
#include "localiser_options.hpp"
#include "world_model.hpp"

namespace structloc::localisation {

// How large an extractor's buffers must be so that updates never allocate.
struct ExtractorCapacity {
  size_t beams = 0;
  size_t wall_lines = 0;  // groups of collinear walls (expected walls at most)
  size_t corners = 0;
  size_t cylinders = 0;
};

// The extractors enabled in `options`, in the order of the parameter file's
// sections (walls first: later kinds may read the walls' measurements).
std::vector<std::unique_ptr<FeatureExtractor>> MakeFeatureExtractors(
    const LocaliserOptions& options, const ExtractorCapacity& capacity);

}  // namespace structloc::localisation
