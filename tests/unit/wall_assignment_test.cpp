// The window-to-wall assignment tests only the walls near a reference line
// (GateCandidates in wall_clustering.cpp), for speed. These tests hold it to
// the thesis' rule (3.5.3, EQ 23-25) applied to every expected wall: each
// window joins the nearest wall within both gates (WallGate), or none.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "structloc/localisation_core/features/walls/wall_clustering.hpp"

namespace structloc::localisation_core {
namespace {

// The rule over all walls: the fixed gates (WallGate) only, ties to the
// lower index.
std::vector<int> AssignOverAllWalls(const std::vector<WindowLine>& windows,
                                    const ExpectedWalls& expected, const WallClusterOptions& o) {
  std::vector<int> out(windows.size(), -1);
  const WallGate gate(o);
  for (size_t i = 0; i < windows.size(); ++i) {
    if (!windows[i].valid) continue;
    double best_d = 3.0;
    for (size_t e = 0; e < expected.walls.size(); ++e) {
      double d;
      if (gate.Nearer(OffsetFrom(windows[i].line, expected.walls[e]), best_d, &d)) {
        out[i] = static_cast<int>(e);
        best_d = d;
      }
    }
  }
  return out;
}

WindowLine Line(double r, double alpha) {
  WindowLine w;
  w.valid = true;
  w.line.r = std::abs(r);
  w.line.cos_alpha = std::copysign(1.0, r) * std::cos(alpha);
  w.line.sin_alpha = std::copysign(1.0, r) * std::sin(alpha);
  w.line.degenerate = false;
  return w;
}

// Window lines as a scan gives them: runs that wander near one wall (some
// across its gates), jumps to another, invalid windows between.
std::vector<WindowLine> ScanLikeWindows(const ExpectedWalls& expected, const WallClusterOptions& o,
                                        std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<size_t> pick(0, expected.walls.size() - 1);
  std::vector<WindowLine> windows;
  while (windows.size() < 2000) {
    const auto& x = expected.walls[pick(rng)];
    double r = x.r, alpha = std::atan2(x.s, x.c);
    const int run = 1 + static_cast<int>(30 * (unit(rng) + 1.0));
    for (int k = 0; k < run; ++k) {
      r += 0.6 * o.gate_r_m * unit(rng);
      alpha += 0.6 * o.gate_alpha_rad * unit(rng);
      windows.push_back(Line(r, alpha));
      if (unit(rng) > 0.9) windows.back().valid = false;
    }
  }
  return windows;
}

ExpectedWalls RandomWalls(int count, std::mt19937& rng) {
  std::uniform_real_distribution<double> range(0.0, 8.0), angle(-geometry::kPi, geometry::kPi);
  ExpectedWalls f;
  for (int i = 0; i < count; ++i) {
    ExpectedWall e;
    e.line_index = i;
    e.r = range(rng);
    const double alpha = angle(rng);
    e.c = std::cos(alpha);
    e.s = std::sin(alpha);
    f.walls.push_back(e);
  }
  return f;
}

TEST(WallAssignment, EqualsTheNearestWallWithinTheGatesOverAllWalls) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> gate_r(0.02, 1.0), gate_alpha(0.01, 1.55);
  for (int trial = 0; trial < 200; ++trial) {
    WallClusterOptions o;
    o.gate_r_m = gate_r(rng);
    o.gate_alpha_rad = gate_alpha(rng);
    o.extent_margin_m = 0.0;  // the fixed gates only
    const ExpectedWalls expected = RandomWalls(1 + trial % 40, rng);
    const auto windows = ScanLikeWindows(expected, o, rng);
    WallClusterWork work;
    std::vector<int> assignment;
    AssignWindowsByExpectation(windows, expected, {}, Eigen::Matrix3d::Identity(), o, work,
                               assignment);
    ASSERT_EQ(assignment, AssignOverAllWalls(windows, expected, o))
        << "trial " << trial << ", gates " << o.gate_r_m << " m, " << o.gate_alpha_rad << " rad";
  }
}

TEST(WallAssignment, ParallelWallsCloserThanTheGateGoToTheNearer) {
  ExpectedWalls f;
  for (const double r : {2.0, 2.15, 2.3}) {
    ExpectedWall e;
    e.line_index = static_cast<int>(f.walls.size());
    e.r = r;
    e.c = 0.0;
    e.s = 1.0;
    f.walls.push_back(e);
  }
  WallClusterOptions o;
  o.extent_margin_m = 0.0;
  const std::vector<WindowLine> windows = {
      Line(2.01, geometry::kHalfPi), Line(2.1, geometry::kHalfPi), Line(2.2, geometry::kHalfPi),
      Line(2.31, geometry::kHalfPi), Line(2.6, geometry::kHalfPi)};
  WallClusterWork work;
  std::vector<int> assignment;
  AssignWindowsByExpectation(windows, f, {}, Eigen::Matrix3d::Identity(), o, work, assignment);
  EXPECT_EQ(assignment, (std::vector<int>{0, 1, 1, 2, -1}));
}

}  // namespace
}  // namespace structloc::localisation_core
