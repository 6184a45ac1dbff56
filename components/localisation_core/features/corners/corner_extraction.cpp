// Corner extraction (see header).
#include "structloc/localisation_core/features/corners/corner_extraction.hpp"

#include <Eigen/Dense>
#include <algorithm>
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

void CornerWork::Reserve(size_t windows, size_t expected) {
  sums.reserve(expected);
  turn.reserve(2 * windows + 1);
}

namespace {

// asin(1/2) / (1/2) = (pi / 6) / (1 / 2), rounded up.
constexpr double kSmallTurnFactor = 1.0472;

// work.turn[j]: a bound on the angle the normal turns from window 0 to window
// j through every window between. A step between two usable windows whose
// normals lie within 90 deg turns by asin |sin|, at most pi/2 |sin|, and at
// most (pi/6) / (1/2) |sin| while |sin| <= 1/2 (asin(x) / x grows with x);
// any other step counts as a full turn.
void BoundTurns(const std::vector<WindowLine>& windows, bool wraps, size_t reach,
                std::vector<double>& turn) {
  const size_t n = windows.size();
  const size_t steps = wraps ? n + reach : n - 1;
  turn.resize(steps + 1);
  double sum = 0.0;
  turn[0] = sum;
  size_t ia = 0, ib = n > 1 ? 1 : 0;  // j and j + 1, wrapped
  for (size_t j = 0; j < steps; ++j, ia = ib, ib = ib + 1 < n ? ib + 1 : 0) {
    const auto& a = windows[ia];
    const auto& b = windows[ib];
    const double cross = a.line.cos_alpha * b.line.sin_alpha - a.line.sin_alpha * b.line.cos_alpha;
    const double dot = a.line.cos_alpha * b.line.cos_alpha + a.line.sin_alpha * b.line.sin_alpha;
    const double sin = std::abs(cross);
    const double factor = sin <= 0.5 ? kSmallTurnFactor : geometry::kHalfPi;
    const bool bounded = a.valid & b.valid & (dot >= 0.0);
    sum += bounded ? factor * sin : geometry::kPi;
    turn[j + 1] = sum;
  }
}

}  // namespace

void ExtractCorners(const std::vector<WindowLine>& windows, bool wraps,
                    const std::vector<ExpectedPoint>& expected, const CornerOptions& o,
                    int window_points, CornerWork& work, std::vector<PointCluster>& out) {
  out.clear();
  const size_t ne = expected.size();
  const size_t n = windows.size();
  if (ne == 0 || n == 0) return;
  work.sums.assign(ne, PointSums{});
  const double min_sin = std::cos(o.angle_tolerance_rad);  // |sin(angle)| near 1
  const double gate2 = o.gate_m * o.gate_m;
  const size_t k = static_cast<size_t>(o.next_windows);
  // The next k usable windows: windows straddling the corner itself fail the
  // rms check, so the search looks up to one window length further.
  // (Never past the window itself in a wrapping scan.)
  const size_t reach = std::min(k + static_cast<size_t>(window_points), n);
  // A window whose normal cannot turn within reach by the angle whose sine
  // passes the test below meets none of them at a corner (the margins cover
  // rounding in the sine and in the bound).
  BoundTurns(windows, wraps, reach, work.turn);
  const double min_turn = std::asin(std::max(0.0, min_sin - 1e-15)) - 1e-9;
  const size_t last = work.turn.size() - 1;
  for (size_t i = 0; i < n; ++i) {
    if (!windows[i].valid) continue;
    if (work.turn[std::min(i + reach, last)] - work.turn[i] < min_turn) continue;
    const auto& p = windows[i].line;
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
      if (e >= 0) work.sums[static_cast<size_t>(e)].Add(x, y);
    }
  }
  for (size_t e = 0; e < ne; ++e) {
    if (work.sums[e].n < o.min_cluster_size) continue;
    out.push_back(work.sums[e].ToCluster(static_cast<int>(e), window_points, o.min_point_sigma_m));
  }
}

}  // namespace structloc::localisation_core
