// Step 5 (thesis 3.5.6, EQ 36-40): cylinders from sliding algebraic circle fits.
// Only windows near an expected pillar are fitted (their centroid within
// candidate_gate_m of the expected surface), solutions need a plausible radius
// and fit quality Q = 1 / sum(residual^2) above a threshold, and are gated in
// (xc, yc) around the expected centre. Beyond the thesis, the cluster's centre
// is refined by a geometric fit with the model radius over all member points.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "structloc/fitting/circle_fit.hpp"
#include "structloc/localisation_core/expectation/expected_points.hpp"
#include "structloc/localisation_core/features/point_cluster.hpp"
#include "structloc/localisation_core/scan/line_fit.hpp"

namespace structloc::localisation_core {

struct CylinderOptions {
  double candidate_gate_m = 0.2;     // window centroid to expected surface
  double radius_tolerance_m = 0.05;  // |fitted radius - model radius|
  double min_quality = 100.0;        // EQ 40 threshold, 1/m^4
  double gate_m = 0.2;               // fitted centre to expected centre
  int min_cluster_size = 1;
  double min_point_sigma_m = 0.002;  // floor of the per-point noise for the covariance
  double map_sigma_m = 0.0;  // the map's error of a pillar centre, 1 sigma per axis (0: exact)
  double gate_chi2 = 0.0;    // Mahalanobis gate, 2 dof (point_gate.hpp; 0: gate_m only)
};

using fitting::CircleFit;

// Algebraic circle fit (EQ 38, the fitting library's) through `count` points
// starting at `first` (indices wrap modulo the point count).
inline CircleFit FitCircle(const ScanPoints& points, size_t first, size_t count) {
  return fitting::FitCircle(points.x, points.y, first, count);
}

// The ring around an expected pillar's surface that a candidate window's
// centroid lies in: its centre (sensor frame) and squared radii.
struct CandidateRing {
  double x, y, lo2, hi2;
};

// The windows (indices, in order) whose centroid lies in one of `rings`:
// only windows near an expected pillar are fitted. Windows are taken in
// blocks, and a block whose centroids' bounding box lies beyond every ring's
// outer radius is skipped whole (each centroid is at least as far as the
// box, also in floating point), so that most windows of a scan test no ring.
void CandidateWindows(const std::vector<WindowLine>& windows,
                      const std::vector<CandidateRing>& rings, std::vector<int>& candidates);

// Where one pillar's windows labelled points: [begin, end), end past the
// point count where the span wraps to the first points. Each window added
// starts at a point (first < the point count).
struct LabelSpan {
  size_t begin = std::numeric_limits<size_t>::max(), end = 0;
  void Add(size_t first, size_t count) {
    begin = std::min(begin, first);
    end = std::max(end, first + count);
  }
};

// The points labelled `label` (indices, in scan order), looked for only
// within `span` (of windows starting at points of `labels`).
void CollectLabelled(const std::vector<int>& labels, const LabelSpan& span, int label,
                     std::vector<int>& members);

struct CylinderWork {
  std::vector<CandidateRing> ring;  // per expected pillar
  std::vector<int> candidates;      // CandidateWindows
  std::vector<PointSums> sums;
  std::vector<int> point_label;
  std::vector<LabelSpan> labelled;  // per expected pillar
  std::vector<int> members;         // one pillar's points, for its refinement
  void Reserve(size_t points, size_t expected);
};

void ExtractCylinders(const std::vector<WindowLine>& windows, const ScanPoints& points,
                      const std::vector<ExpectedPoint>& expected, const CylinderOptions& options,
                      int window_points, CylinderWork& work, std::vector<PointCluster>& out);

}  // namespace structloc::localisation_core
