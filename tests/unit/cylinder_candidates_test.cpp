// The pillar step skips work for speed (cylinder_extraction.cpp): blocks of
// windows far from every expected pillar, and the points outside the span its
// windows labelled. These tests hold both to the plain rules: the candidate
// windows are those whose centroid lies in some ring (thesis 3.5.6), and a
// pillar's points are every point carrying its label, in scan order.
#include <gtest/gtest.h>

#include <random>

#include "structloc/localisation_core/features/cylinders/cylinder_extraction.hpp"

namespace structloc::localisation_core {
namespace {

std::vector<int> CandidatesOverEveryWindow(const std::vector<WindowLine>& windows,
                                           const std::vector<CandidateRing>& rings) {
  std::vector<int> out;
  for (size_t i = 0; i < windows.size(); ++i) {
    for (const auto& ring : rings) {
      const double dx = windows[i].line.xm - ring.x, dy = windows[i].line.ym - ring.y;
      const double d2 = dx * dx + dy * dy;
      if (d2 >= ring.lo2 && d2 <= ring.hi2) {
        out.push_back(static_cast<int>(i));
        break;
      }
    }
  }
  return out;
}

// Window centroids as a scan gives them: a walk along the walls with jumps,
// passing near the pillars now and then.
std::vector<WindowLine> ScanLikeCentroids(size_t count, std::mt19937& rng) {
  std::uniform_real_distribution<double> step(-0.05, 0.08), place(-6.0, 6.0), unit(0.0, 1.0);
  std::vector<WindowLine> windows(count);
  double x = place(rng), y = place(rng);
  for (auto& w : windows) {
    if (unit(rng) < 0.03) {  // a depth jump
      x = place(rng);
      y = place(rng);
    }
    x += step(rng);
    y += step(rng);
    w.line.xm = x;
    w.line.ym = y;
  }
  return windows;
}

TEST(CylinderCandidates, AreTheWindowsInsideSomeRing) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> place(-6.0, 6.0), radius(0.05, 0.5), gate(0.05, 0.3);
  size_t candidates_seen = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // Every block length remainder, and scans with no window at all.
    const auto windows = ScanLikeCentroids(static_cast<size_t>(trial * 7 % 901), rng);
    std::vector<CandidateRing> rings;
    for (int e = 0, n = trial % 5; e < n; ++e) {
      // Half the rings centred on a window's centroid, so that windows fall in them.
      double x = place(rng), y = place(rng);
      if (!windows.empty() && e % 2 == 0) {
        const auto& l = windows[static_cast<size_t>(rng() % windows.size())].line;
        x = l.xm + 0.2;
        y = l.ym;
      }
      const double r = radius(rng), g = gate(rng);
      const double lo = std::max(0.0, r - g), hi = r + g;
      rings.push_back({x, y, lo * lo, hi * hi});
    }
    std::vector<int> blockwise;
    CandidateWindows(windows, rings, blockwise);
    const auto over_every_window = CandidatesOverEveryWindow(windows, rings);
    ASSERT_EQ(blockwise, over_every_window) << "trial " << trial;
    candidates_seen += over_every_window.size();
  }
  EXPECT_GT(candidates_seen, 1000u) << "the trials must put windows inside rings";
}

TEST(CylinderCandidates, ACentroidOnTheOuterRadiusIsACandidate) {
  std::vector<WindowLine> windows(40);
  for (size_t i = 0; i < windows.size(); ++i) {
    windows[i].line.xm = 10.0 + static_cast<double>(i);
    windows[i].line.ym = 0.0;
  }
  windows[37].line.xm = 0.5;  // exactly on the ring's outer radius, in a block of far ones
  std::vector<int> out;
  CandidateWindows(windows, {{0.0, 0.0, 0.0, 0.25}}, out);
  EXPECT_EQ(out, (std::vector<int>{37}));
}

// Labels as the pillar step sets them: windows of `window_points` points,
// each of one pillar, a point claimed by two pillars marked -2.
TEST(CylinderMembers, AreEveryPointWithTheLabelInScanOrder) {
  std::mt19937 rng(5);
  size_t members_seen = 0, wrapped_spans = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const size_t points = 8 + rng() % 500, window_points = 3 + rng() % 6, pillars = 1 + rng() % 3;
    const bool wraps = trial % 2 == 0;
    std::vector<int> labels(points, -1);
    std::vector<LabelSpan> spans(pillars);
    const size_t windows = rng() % 40;
    for (size_t k = 0; k < windows; ++k) {
      const size_t first =
          wraps ? rng() % points : rng() % (points - std::min(points, window_points) + 1);
      const int e = static_cast<int>(rng() % pillars);
      // A pillar's windows come in runs, as along a pillar's surface.
      for (size_t run = 0, n = 1 + rng() % 6; run < n; ++run) {
        const size_t f =
            wraps ? (first + run) % points : std::min(first + run, points - window_points);
        spans[static_cast<size_t>(e)].Add(f, window_points);
        for (size_t j = 0; j < window_points; ++j) {
          int& label = labels[(f + j) % points];
          label = (label == -1 || label == e) ? e : -2;
        }
      }
    }
    for (size_t e = 0; e < pillars; ++e) {
      std::vector<int> every_labelled;
      for (size_t k = 0; k < points; ++k) {
        if (labels[k] == static_cast<int>(e)) every_labelled.push_back(static_cast<int>(k));
      }
      std::vector<int> within_span{-7};  // cleared first
      CollectLabelled(labels, spans[e], static_cast<int>(e), within_span);
      ASSERT_EQ(within_span, every_labelled) << "trial " << trial << ", pillar " << e;
      members_seen += every_labelled.size();
      wrapped_spans += spans[e].end > points && spans[e].end - spans[e].begin < points;
    }
  }
  EXPECT_GT(members_seen, 10000u);
  EXPECT_GT(wrapped_spans, 20u) << "spans across the scan's end must be among the trials";
}

}  // namespace
}  // namespace structloc::localisation_core
