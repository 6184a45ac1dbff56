// The quantile the map reports print ("90 % below"), one definition for all of
// them: the value at rank share * (n - 1) of the sorted values. DDS-free.
#pragma once

#include <algorithm>
#include <vector>

namespace structloc::map_building {

// 0 for no values; `share` in [0, 1].
inline double Quantile(std::vector<double> values, double share) {
  if (values.empty()) return 0.0;
  const auto at =
      values.begin() + static_cast<long>(share * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

}  // namespace structloc::map_building
