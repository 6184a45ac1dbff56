// ExtractCorners skips the windows whose normal cannot turn far enough within
// reach to meet another at a corner (a bound on the turn). These tests hold
// it to the thesis' rule (3.5.4, EQ 31) applied to every window: each usable
// window's line crossed with the next k usable ones within reach.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "structloc/localisation_core/features/corners/corner_extraction.hpp"

namespace structloc::localisation_core {
namespace {

// The rule over every window, without the bound: the crossings summed per
// expected corner.
std::vector<PointSums> CrossEveryWindow(const std::vector<WindowLine>& windows, bool wraps,
                                        const std::vector<ExpectedPoint>& expected,
                                        const CornerOptions& o, int window_points) {
  std::vector<PointSums> sums(expected.size());
  const size_t n = windows.size();
  const size_t k = static_cast<size_t>(o.next_windows);
  const size_t reach = k + static_cast<size_t>(window_points);
  for (size_t i = 0; i < n; ++i) {
    if (!windows[i].valid) continue;
    const auto& p = windows[i].line;
    size_t used = 0;
    for (size_t j = 1; j <= reach && used < k; ++j) {
      if (!wraps && i + j >= n) break;
      const auto& q = windows[(i + j) % n];
      if (!q.valid) continue;
      ++used;
      const double det = p.cos_alpha * q.line.sin_alpha - p.sin_alpha * q.line.cos_alpha;
      if (std::abs(det) < std::cos(o.angle_tolerance_rad)) continue;
      const double x = (p.r * q.line.sin_alpha - q.line.r * p.sin_alpha) / det;
      const double y = (p.cos_alpha * q.line.r - q.line.cos_alpha * p.r) / det;
      const int e = NearestWithin(expected, x, y, o.gate_m * o.gate_m);
      if (e >= 0) sums[static_cast<size_t>(e)].Add(x, y);
    }
  }
  return sums;
}

WindowLine Line(double r, double alpha, bool valid) {
  WindowLine w;
  w.valid = valid;
  w.line.r = r;
  w.line.cos_alpha = std::cos(alpha);
  w.line.sin_alpha = std::sin(alpha);
  w.line.degenerate = false;
  return w;
}

// Window lines as a scan of a room gives them: runs along walls whose normal
// wanders by noise, turns at corners (some sharp, some gradual), invalid
// windows where the rms check fails.
std::vector<WindowLine> RoomLikeWindows(std::mt19937& rng, double noise_rad) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<WindowLine> windows;
  double alpha = 0.0;
  while (windows.size() < 1500) {
    const int run = 5 + static_cast<int>(20 * (unit(rng) + 1.0));
    const double r = 2.0 + unit(rng);
    for (int k = 0; k < run; ++k) {
      windows.push_back(Line(r, alpha + noise_rad * unit(rng), unit(rng) < 0.9));
    }
    // A corner (a turn of about 90 deg, or of any angle, at once or over a
    // few windows), or a gentle bend.
    const double kind = unit(rng);
    const double turn = kind > 0.3    ? geometry::kHalfPi * (1.0 + 0.2 * unit(rng))
                        : kind > -0.4 ? geometry::kHalfPi * (1.0 + 0.9 * unit(rng))
                                      : 0.3;
    const int steps = 1 + static_cast<int>(2 * (unit(rng) + 1.0));
    for (int k = 0; k < steps; ++k) {
      alpha += turn / steps;
      windows.push_back(Line(r, alpha, unit(rng) < 0.5));
    }
  }
  return windows;
}

TEST(CornerCrossings, EqualTheCrossingsOfEveryWindow) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 100; ++trial) {
    // Every next_windows with both kinds of scan and both noise levels.
    const bool wraps = (trial / 6) % 2 == 0;
    const auto windows = RoomLikeWindows(rng, (trial / 12) % 2 == 0 ? 0.3 : 0.02);
    // Expected corners where the crossings fall: every crossing counts.
    std::vector<ExpectedPoint> expected;
    for (double x = -6.0; x <= 6.0; x += 0.3) {
      for (double y = -6.0; y <= 6.0; y += 0.3) expected.push_back({0, 0, {x, y}, {x, y}, 0.0});
    }
    CornerOptions o;
    o.next_windows = 1 + trial % 6;
    o.angle_tolerance_rad = 0.1 + 0.01 * trial;
    o.min_cluster_size = 1;
    CornerWork work;
    std::vector<PointCluster> out;
    ExtractCorners(windows, wraps, expected, o, 7, work, out);
    const auto sums = CrossEveryWindow(windows, wraps, expected, o, 7);
    size_t found = 0;
    for (size_t e = 0; e < sums.size(); ++e) found += sums[e].n >= 1 ? 1 : 0;
    ASSERT_EQ(out.size(), found) << "trial " << trial;
    for (const auto& c : out) {
      const auto& s = sums[static_cast<size_t>(c.expected_index)];
      ASSERT_EQ(c.members, static_cast<int>(s.n)) << "trial " << trial;
      ASSERT_EQ(c.mean.x(), s.Mean().x()) << "trial " << trial;
      ASSERT_EQ(c.mean.y(), s.Mean().y()) << "trial " << trial;
    }
  }
}

}  // namespace
}  // namespace structloc::localisation_core
