// Newest-pose age quantiles (see header).
#include "structloc/evaluation/pose_age.hpp"

#include <algorithm>

namespace structloc::evaluation {

double NewestPoseAgeQuantile(const std::vector<double>& arrivals_s, double q) {
  if (arrivals_s.size() < 2) return 0.0;
  std::vector<double> gaps;
  gaps.reserve(arrivals_s.size() - 1);
  for (size_t i = 1; i < arrivals_s.size(); ++i) {
    gaps.push_back(std::max(0.0, arrivals_s[i] - arrivals_s[i - 1]));
  }
  std::sort(gaps.begin(), gaps.end());
  double total = 0.0;
  for (const double g : gaps) total += g;
  if (total <= 0.0) return 0.0;
  // The time the age exceeds `a` is the sum over gaps of max(0, g - a); find
  // the `a` where that is (1 - q) of the total, walking the sorted gaps from
  // the largest (between two gaps the excess falls linearly in `a`).
  const double allowed = (1.0 - std::clamp(q, 0.0, 1.0)) * total;
  double excess_slope = 0.0;  // gaps longer than the current `a`
  double excess = 0.0;        // time above the current `a`
  double a = gaps.back();
  for (size_t i = gaps.size(); i-- > 0;) {
    const double next = i > 0 ? gaps[i - 1] : 0.0;
    excess_slope += 1.0;
    const double at_next = excess + excess_slope * (a - next);
    if (at_next >= allowed) return a - (allowed - excess) / excess_slope;
    excess = at_next;
    a = next;
  }
  return 0.0;
}

}  // namespace structloc::evaluation
