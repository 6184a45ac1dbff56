// The whole-scan check traces each beam through the map's wall cells,
// skipping the samples the distance field shows clear (CrossesWall,
// wall_crossing.hpp). These tests hold the tracing to testing every sample on
// any distance field, and the localiser's verdicts to the geometry: a beam to
// a far wall is blocked where a short wall stands in its way and clear where
// it passes beside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "structloc/localisation_core/global/global_localiser.hpp"
#include "structloc/localisation_core/global/wall_crossing.hpp"

namespace structloc::localisation_core {
namespace {

// The tracing without skips: every sample from `from` to `to`, in order.
bool CrossesWallAtSomeSample(const WallDistanceField& f, const Eigen::Vector2d& from,
                             const Eigen::Vector2d& to) {
  const double res = f.resolution_m;
  const int samples = static_cast<int>((to - from).norm() / (0.5 * res));
  for (int i = 1; i < samples; ++i) {
    const double x = (from.x() - f.x0) / res + (to.x() - from.x()) / (res * samples) * i;
    const double y = (from.y() - f.y0) / res + (to.y() - from.y()) / (res * samples) * i;
    if (!(x >= 0.0 && y >= 0.0 && x < f.width && y < f.height)) return false;
    if ((*f.cells)[static_cast<size_t>(static_cast<int>(y)) * f.width + static_cast<int>(x)] == 0)
      return true;
  }
  return false;
}

// A field of scattered wall cells and wall runs at any angle, each cell
// holding its floored distance to the nearest wall cell (exact, by testing
// every wall cell).
std::vector<uint8_t> RandomWallField(int width, int height, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<int> walls;
  const double density = 0.002 + 0.02 * unit(rng);
  for (int i = 0; i < width * height; ++i) {
    if (unit(rng) < density) walls.push_back(i);
  }
  for (int run = 0; run < 3; ++run) {
    const double x = unit(rng) * width, y = unit(rng) * height, a = unit(rng) * 2.0 * geometry::kPi;
    for (double t = 0.0; t < 30.0; t += 0.25) {
      const int c = static_cast<int>(std::floor(x + t * std::cos(a)));
      const int r = static_cast<int>(std::floor(y + t * std::sin(a)));
      if (c >= 0 && r >= 0 && c < width && r < height) walls.push_back(r * width + c);
    }
  }
  std::vector<uint8_t> cells(static_cast<size_t>(width) * height, 255);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      double nearest = 1e9;
      for (const int w : walls) {
        nearest = std::min(nearest, std::hypot(c - w % width, r - w / width));
      }
      cells[static_cast<size_t>(r) * width + c] =
          static_cast<uint8_t>(std::min(255.0, std::floor(nearest)));
    }
  }
  return cells;
}

TEST(BeamVerdicts, TheSkippingTraceIsTestingEverySample) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  size_t beams = 0, blocked = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int width = 20 + static_cast<int>(rng() % 80), height = 20 + static_cast<int>(rng() % 80);
    const std::vector<uint8_t> cells = RandomWallField(width, height, rng);
    const double res = std::vector<double>{0.025, 0.03, 0.05, 0.07, 0.1}[rng() % 5];
    const WallDistanceField field{
        &cells, width, height, (unit(rng) - 0.5) * 200.0, (unit(rng) - 0.5) * 200.0, res};
    std::vector<int> wall_cells;
    for (int i = 0; i < width * height; ++i) {
      if (cells[static_cast<size_t>(i)] == 0) wall_cells.push_back(i);
    }
    // Beams from inside the grid: to anywhere near it (some leaving it), or
    // ending in a wall cell or just past it, where a skip too long hops the
    // last samples.
    for (int b = 0; b < 3000; ++b) {
      const Eigen::Vector2d from(field.x0 + unit(rng) * width * res,
                                 field.y0 + unit(rng) * height * res);
      Eigen::Vector2d to(field.x0 + (1.4 * unit(rng) - 0.2) * width * res,
                         field.y0 + (1.4 * unit(rng) - 0.2) * height * res);
      if (b % 2 == 0 && !wall_cells.empty()) {
        const int w = wall_cells[rng() % wall_cells.size()];
        const Eigen::Vector2d in_wall(field.x0 + (w % width + unit(rng)) * res,
                                      field.y0 + (w / width + unit(rng)) * res);
        to = from + (in_wall - from) * (1.0 + unit(rng) * res / (in_wall - from).norm());
      }
      const bool every = CrossesWallAtSomeSample(field, from, to);
      ASSERT_EQ(CrossesWall(field, from, to), every)
          << "trial " << trial << ", beam " << b << " from (" << from.transpose() << ") to ("
          << to.transpose() << ")";
      ++beams;
      blocked += every;
    }
  }
  EXPECT_GT(blocked, beams / 10);
  EXPECT_LT(blocked, beams - beams / 10);
}

// One of the rare beams (a few in ten million at random) on which a skip
// that keeps a margin of one cell instead of the cell's diagonal hops the
// last sample: it ends just inside a lone wall cell, near its corner.
TEST(BeamVerdicts, ABeamEndingJustInsideALoneWallCellIsBlocked) {
  constexpr int kSide = 40, kWall = 20;
  std::vector<uint8_t> cells(kSide * kSide);
  for (int r = 0; r < kSide; ++r) {
    for (int c = 0; c < kSide; ++c) {
      cells[static_cast<size_t>(r * kSide + c)] =
          static_cast<uint8_t>(std::floor(std::hypot(c - kWall, r - kWall)));
    }
  }
  const WallDistanceField field{&cells, kSide, kSide, 0.0, 0.0, 1.0};
  const Eigen::Vector2d from(36.631114114977223, 32.4445649658185);
  const Eigen::Vector2d to(20.479420330076341, 20.674316439085107);
  ASSERT_TRUE(CrossesWallAtSomeSample(field, from, to));
  EXPECT_TRUE(CrossesWall(field, from, to));
}

TEST(BeamVerdicts, ABeamIsBlockedExactlyWhereAShortWallStandsInItsWay) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> place(-20.0, 20.0);
  size_t blocked = 0, clear = 0;
  for (int trial = 0; trial < 12; ++trial) {
    // In the scene's own frame: the laser at the origin, a short wall across
    // x = 2 for |y| <= 1, a long one across x = 6; a beam to (6, y) crosses
    // x = 2 at y / 3, so it is blocked for |y| < 3 and clear for |y| > 3. A
    // wall behind the laser puts it inside the map (beams are traced on the
    // map's grid).
    // Turned by quarter turns only: a wall drawn into cells at another angle
    // has cells that meet only at their corners, and a beam may pass between
    // them (the map's resolution, not the tracing, which this test is about).
    const geometry::Pose2D scene{place(rng), place(rng), geometry::kHalfPi * (trial % 4)};
    auto in_map = [&](double x, double y) { return scene.Apply(Eigen::Vector2d(x, y)); };
    const world_model::WorldModel world(
        "beams",
        {world_model::MakeWall(0, in_map(2.0, -1.0), in_map(2.0, 1.0)),
         world_model::MakeWall(1, in_map(6.0, -5.0), in_map(6.0, 5.0)),
         world_model::MakeWall(2, in_map(-1.0, -5.0), in_map(-1.0, 5.0))},
        {}, {});
    const GlobalLocaliser locator(world, GlobalLocaliserOptions{});
    // Readings on the long wall, in the laser frame (the laser at `scene`),
    // away from where the beam grazes the short wall's end (two cells and
    // the rounding of a wall drawn into cells).
    std::vector<Eigen::Vector2d> points;
    std::vector<bool> expect_blocked;
    for (double y = -4.9; y <= 4.9; y += 0.01) {
      const double crossing = std::abs(y) / 3.0;  // where the beam passes x = 2
      if (std::abs(crossing - 1.0) < 0.15) continue;
      points.emplace_back(6.0, y);
      expect_blocked.push_back(crossing < 1.0);
    }
    std::vector<GlobalLocaliser::BeamVerdict> verdicts(points.size(),
                                                       GlobalLocaliser::BeamVerdict::kUnknown);
    locator.ExplainedShare(points, scene, verdicts);
    for (size_t i = 0; i < points.size(); ++i) {
      const auto want = expect_blocked[i] ? GlobalLocaliser::BeamVerdict::kBlocked
                                          : GlobalLocaliser::BeamVerdict::kClear;
      ASSERT_EQ(verdicts[i], want) << "trial " << trial << ", reading at y = " << points[i].y();
      (expect_blocked[i] ? blocked : clear) += 1;
    }
  }
  EXPECT_GT(blocked, 2000u);
  EXPECT_GT(clear, 2000u);
}

}  // namespace
}  // namespace structloc::localisation_core
