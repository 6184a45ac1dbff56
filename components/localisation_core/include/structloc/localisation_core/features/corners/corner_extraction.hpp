// Step 4 (thesis 3.5.4, EQ 31): corners from intersecting each window's line with
// the lines of the next k usable windows when they meet at pi/2 +- tolerance; the
// intersections pile up at each corner and are gated around expected corners.
#pragma once

#include <vector>

#include "structloc/localisation_core/expectation/expected_points.hpp"
#include "structloc/localisation_core/features/point_cluster.hpp"
#include "structloc/localisation_core/scan/line_fit.hpp"

namespace structloc::localisation_core {

struct CornerOptions {
  int next_windows = 5;                            // k: windows after i intersected with i
  double angle_tolerance_rad = geometry::kPi / 8;  // around pi/2
  double gate_m = 0.2;                             // distance gate around an expected corner
  int min_cluster_size = 1;
  double min_point_sigma_m = 0.005;  // floor of a corner's standard deviation
  // A corner where two matched walls meet at an angle whose sine exceeds
  // redundant_min_sin adds nothing they do not already say (a wall passes
  // through the corner when within redundant_wall_distance_m of it); the
  // weighted solver leaves such a corner out so that its covariance does not lie.
  double redundant_wall_distance_m = 0.05;
  double redundant_min_sin = 0.5;  // sin of 30 deg
  double map_sigma_m = 0.0;        // the map's error of a corner, 1 sigma per axis (0: exact)
  double gate_chi2 = 0.0;          // Mahalanobis gate, 2 dof (point_gate.hpp; 0: gate_m only)
};

// Scratch space for ExtractCorners, reused across scans.
struct CornerWork {
  std::vector<PointSums> sums;  // per expected corner
  // Bound on how far the normal turns from window 0 to window j through the
  // windows between (cumulative; continued past the end of a wrapping scan).
  std::vector<double> turn;
  void Reserve(size_t windows, size_t expected);
};

void ExtractCorners(const std::vector<WindowLine>& windows, bool wraps,
                    const std::vector<ExpectedPoint>& expected, const CornerOptions& options,
                    int window_points, CornerWork& work, std::vector<PointCluster>& out);

}  // namespace structloc::localisation_core
