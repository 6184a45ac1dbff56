// The thesis' algebraic circle fit (3.5.5, EQ 38) with its quality (EQ 39-40):
// the localiser fits every sliding window of a scan to find pillars, map
// making every arc-like run of a recording.
#pragma once

#include <cstddef>
#include <vector>

namespace structloc::fitting {

struct CircleFit {
  double xc = 0, yc = 0, radius = 0;
  double quality = 0;  // EQ 40: 1 / the sum of squared algebraic residuals, 1/m^4
  bool ok = false;
};

// The circle through the `count` points (x[i], y[i]) from index `first` on
// (indices wrap modulo x.size(): a scan over a full turn; count <= x.size()),
// computed about their centroid.
CircleFit FitCircle(const std::vector<double>& x, const std::vector<double>& y, size_t first,
                    size_t count);

}  // namespace structloc::fitting
