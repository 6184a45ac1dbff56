// The prefilter's support check and thinning run as one branch-free pass
// (RejectUnsupportedAndThin). These tests hold it to the two steps as the
// thesis describes them (3.5.1), done one after the other with plain loops.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "structloc/localisation_core/scan/prefilter.hpp"

namespace structloc::localisation_core {
namespace {

// Step 1: drop a point farther than max_neighbour_distance_m from both
// neighbours (in a wrapping scan the first and last are neighbours).
ScanPoints DropUnsupported(const ScanPoints& in, const PrefilterOptions& o) {
  const size_t n = in.Size();
  if (n < 3) return in;
  const double far2 = o.max_neighbour_distance_m * o.max_neighbour_distance_m;
  auto far = [&](size_t a, size_t b) {
    const double dx = in.x[a] - in.x[b], dy = in.y[a] - in.y[b];
    return dx * dx + dy * dy > far2;
  };
  ScanPoints out;
  out.wraps = in.wraps;
  for (size_t i = 0; i < n; ++i) {
    const bool far_prev = i > 0 ? far(i, i - 1) : (!in.wraps || far(i, n - 1));
    const bool far_next = i + 1 < n ? far(i, i + 1) : (!in.wraps || far(i, 0));
    if (!(far_prev && far_next)) out.Push(in.x[i], in.y[i], in.beam[i]);
  }
  return out;
}

// Step 2: drop a point closer than min_neighbour_distance_m to the last kept.
ScanPoints ThinOut(const ScanPoints& in, const PrefilterOptions& o) {
  const double near2 = o.min_neighbour_distance_m * o.min_neighbour_distance_m;
  ScanPoints out;
  out.wraps = in.wraps;
  for (size_t i = 0; i < in.Size(); ++i) {
    if (out.Size() > 0) {
      const double dx = in.x[i] - out.x.back(), dy = in.y[i] - out.y.back();
      if (dx * dx + dy * dy < near2) continue;
    }
    out.Push(in.x[i], in.y[i], in.beam[i]);
  }
  return out;
}

TEST(PrefilterPass, EqualsDroppingUnsupportedPointsThenThinning) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    // Runs of points at spacings around both distances, with lone returns.
    ScanPoints points;
    points.wraps = (trial / 50) % 2 == 0;  // every count both ways
    const int count = trial % 50;
    double x = 0.0, y = 0.0;
    for (int i = 0; i < count; ++i) {
      const double step = unit(rng) < 0.2 ? 1.0 : 0.12 * unit(rng);
      x += step * std::cos(0.1 * i);
      y += step * std::sin(0.1 * i);
      points.Push(x, y, i);
    }
    PrefilterOptions o;
    o.max_neighbour_distance_m = 0.1;
    o.min_neighbour_distance_m = 0.04;
    const ScanPoints expected = ThinOut(DropUnsupported(points, o), o);
    const size_t supported = DropUnsupported(points, o).Size();
    PrefilterStats stats;
    RejectUnsupportedAndThin(o, points, stats);
    ASSERT_EQ(points.beam, expected.beam) << "trial " << trial;
    ASSERT_EQ(points.x, expected.x) << "trial " << trial;
    ASSERT_EQ(stats.unsupported, static_cast<size_t>(count) - supported) << "trial " << trial;
    ASSERT_EQ(stats.thinned, supported - expected.Size()) << "trial " << trial;
    ASSERT_EQ(stats.kept, expected.Size()) << "trial " << trial;
  }
}

}  // namespace
}  // namespace structloc::localisation_core
