// Corner extraction (see header).
#include "structloc/localisation_core/features/corners/corner_extraction.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace structloc::localisation_core {

PointCluster PointSums::ToCluster(int index, int window_points, double sigma_floor_m) const {
  PointCluster c;
  c.expected_index = index;
  c.members = static_cast<int>(n);
  c.mean = Mean();
  c.refined = c.mean;
  c.covariance = Scatter() / std::max(1.0, n / window_points) +
                 sigma_floor_m * sigma_floor_m * Eigen::Matrix2d::Identity();
  return c;
}

Eigen::Matrix2d PointSums::Scatter() const {
  const Eigen::Vector2d m = Mean();
  Eigen::Matrix2d c;
  const double k = n > 1 ? 1.0 / (n - 1) : 1.0;
  c(0, 0) = std::max(0.0, (sxx - n * m.x() * m.x()) * k);
  c(1, 1) = std::max(0.0, (syy - n * m.y() * m.y()) * k);
  c(0, 1) = c(1, 0) = (sxy - n * m.x() * m.y()) * k;
  return c;
}

void ExtractCorners(const std::vector<WindowLine>& windows, bool wraps,
                    const std::vector<ExpectedPoint>& expected, const CornerOptions& o,
                    int window_points, std::vector<PointSums>& work,
                    std::vector<PointCluster>& out) {
  out.clear();
  const size_t ne = expected.size();
  if (ne == 0) return;
  work.assign(ne, PointSums{});
  const double min_sin = std::cos(o.angle_tolerance_rad);  // |sin(angle)| near 1
  const double gate2 = o.gate_m * o.gate_m;
  const size_t n = windows.size();
  const size_t k = static_cast<size_t>(o.next_windows);
  for (size_t i = 0; i < n; ++i) {
    if (!windows[i].valid) continue;
    const auto& p = windows[i].line;
    // The next k usable windows: windows straddling the corner itself fail the
    // rms check, so the search looks up to one window length further.
    const size_t reach = k + static_cast<size_t>(window_points);
    size_t used = 0;
    for (size_t j = 1; j <= reach && used < k; ++j) {
      if (!wraps && i + j >= n) break;
      const auto& q = windows[i + j < n ? i + j : i + j - n];
      if (!q.valid) continue;
      ++used;
      const double det = p.cos_alpha * q.line.sin_alpha - p.sin_alpha * q.line.cos_alpha;
      if (std::abs(det) < min_sin) continue;
      // EQ 31 by Cramer's rule.
      const double x = (p.r * q.line.sin_alpha - q.line.r * p.sin_alpha) / det;
      const double y = (p.cos_alpha * q.line.r - q.line.cos_alpha * p.r) / det;
      const int e = NearestWithin(expected, x, y, gate2);
      if (e >= 0) work[static_cast<size_t>(e)].Add(x, y);
    }
  }
  for (size_t e = 0; e < ne; ++e) {
    if (work[e].n < o.min_cluster_size) continue;
    out.push_back(work[e].ToCluster(static_cast<int>(e), window_points, o.min_point_sigma_m));
  }
}

}  // namespace structloc::localisation_core
