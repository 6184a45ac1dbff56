// Kuemmerle et al. 2009's metric: a trajectory judged by the relative poses
// it gives between pairs of scans against hand-verified ones (relations
// files), so that a map's global frame and its slow drift do not count, only
// what a robot navigating by the map would suffer. Per relation the error is
// the estimated relation minus the reference, translation (its length) and
// rotation (wrapped) apart; reported as their mean and standard deviation,
// as the paper's tables. DDS-free.
#pragma once

#include <cstddef>
#include <vector>

#include "structloc/log_formats/relations_reader.hpp"
#include "structloc/log_formats/tum_reader.hpp"

namespace structloc::replay {

struct RelationError {
  size_t used = 0;     // relations whose two stamps the trajectory has
  size_t missing = 0;  // relations with a stamp the trajectory lacks
  double translation_mean_m = 0.0, translation_std_m = 0.0;
  double rotation_mean_rad = 0.0, rotation_std_rad = 0.0;
};

// `trajectory` in time order; a relation's stamp matches the trajectory's
// nearest pose within `tolerance_s` (the paper's 0.1 s).
RelationError CompareRelations(const std::vector<log_formats::StampedPose>& trajectory,
                               const std::vector<log_formats::Relation>& relations,
                               double tolerance_s = 0.1);

}  // namespace structloc::replay
