// The whole-scan check traces each beam through the map's wall cells,
// skipping the samples the distance field shows clear (CrossesWall in
// global_localiser.cpp). This test holds its verdicts to the geometry: a beam
// to a far wall is blocked where a short wall stands in its way and clear
// where it passes beside it, for the scene placed anywhere in the plane and
// facing any of four ways, so that a skip that hops over a wall fails it.
#include <gtest/gtest.h>

#include <random>

#include "structloc/localisation_core/global/global_localiser.hpp"

namespace structloc::localisation_core {
namespace {

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
