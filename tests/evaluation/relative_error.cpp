// Kuemmerle et al. 2009's relation metric with the relations drawn from a
// reference path instead of verified by hand: from every pose of the
// reference, the relation to the first pose at least D metres of travel
// later, for each D asked, judged on an estimate (replay::CompareRelations:
// mean and standard deviation of the translation and rotation errors). Short
// D measure what a robot navigating by a map suffers, long D the map's
// global shape, which one alignment of the whole path mixes with the rest.
// Used to ask whether localisation on a self-built map is as good locally as
// on the map built on the reference poses, and from what distance the two
// part (issue 41). Also printed: the median ratio of the estimate's
// straight-line distance to the reference's over the relations whose
// reference distance is at least D/2, which tells a path or map scaled
// against the reference (a uniform scale shows at every D) from one bent.
//   structloc_relative_error ESTIMATE.tum REFERENCE.tum [D_M ...] (default 1 5 20)
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "structloc/log_formats/relations_reader.hpp"
#include "structloc/log_formats/tum_reader.hpp"
#include "structloc/replay/relation_error.hpp"

namespace {

using structloc::log_formats::Relation;
using structloc::log_formats::StampedPose;

// From each reference pose, the relation to the first one at least
// `distance_m` of travel later.
std::vector<Relation> RelationsOver(const std::vector<StampedPose>& reference, double distance_m) {
  std::vector<double> travelled(reference.size(), 0.0);
  for (size_t i = 1; i < reference.size(); ++i) {
    travelled[i] = travelled[i - 1] +
                   (reference[i].pose.Translation() - reference[i - 1].pose.Translation()).norm();
  }
  std::vector<Relation> relations;
  size_t j = 0;
  for (size_t i = 0; i < reference.size(); ++i) {
    while (j < reference.size() && travelled[j] - travelled[i] < distance_m) ++j;
    if (j == reference.size()) break;
    relations.push_back({reference[i].stamp, reference[j].stamp,
                         structloc::geometry::Between(reference[i].pose, reference[j].pose)});
  }
  return relations;
}

// The median (the upper of the middle two for an even count) of
// |estimated translation| / |reference translation| over the relations
// whose reference translation is at least `min_length_m`; NaN when none.
double MedianLengthRatio(const std::vector<StampedPose>& estimate,
                         const std::vector<Relation>& relations, double min_length_m) {
  std::vector<double> ratios;
  for (const auto& r : relations) {
    const double reference = std::hypot(r.relative.x, r.relative.y);
    const auto* a = structloc::log_formats::Nearest(estimate, r.t1, 1e-3);
    const auto* b = structloc::log_formats::Nearest(estimate, r.t2, 1e-3);
    if (reference < min_length_m || a == nullptr || b == nullptr) continue;
    ratios.push_back((b->pose.Translation() - a->pose.Translation()).norm() / reference);
  }
  if (ratios.empty()) return std::nan("");
  const auto middle = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
  std::nth_element(ratios.begin(), middle, ratios.end());
  return *middle;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: structloc_relative_error ESTIMATE.tum REFERENCE.tum [D_M ...] "
                 "(default 1 5 20)\n");
    return 2;
  }
  try {
    std::vector<double> distances;
    for (int a = 3; a < argc; ++a) distances.push_back(std::atof(argv[a]));
    if (distances.empty()) distances = {1.0, 5.0, 20.0};
    for (double d : distances) {
      if (!(d > 0)) throw std::invalid_argument("every D_M must be > 0");
    }
    const auto estimate = structloc::log_formats::ReadTum(argv[1]);
    const auto reference = structloc::log_formats::ReadTum(argv[2]);
    constexpr double kDeg = 3.14159265358979323846 / 180.0;
    for (double d : distances) {
      // The stamps are the same log's: matched within a millisecond.
      const auto relations = RelationsOver(reference, d);
      const auto e = structloc::replay::CompareRelations(estimate, relations, 1e-3);
      std::printf(
          "over %g m: %.1f +- %.1f mm, %.2f +- %.2f deg (%zu relations, %zu not in the "
          "estimate); length ratio %.4f\n",
          d, 1e3 * e.translation_mean_m, 1e3 * e.translation_std_m, e.rotation_mean_rad / kDeg,
          e.rotation_std_rad / kDeg, e.used, e.missing,
          MedianLengthRatio(estimate, relations, d / 2.0));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "structloc_relative_error: %s\n", e.what());
    return 1;
  }
  return 0;
}
