// The visibility kept for the places the robot passes (issue 37): an entry
// holds within its reach (distance, and heading short of a full circle), the
// nearest entry that holds is found, a computed entry is what the world
// model's own visibility gives there, the entry in use is never replaced, and
// another view empties the cache. And the localiser around it: after the first
// scan an update never computes a visibility itself; Anticipate does, between
// scans, where none holds.
#include <gtest/gtest.h>

#include <random>

#include "office_scene.hpp"
#include "structloc/localisation_core/expectation/visibility_cache.hpp"
#include "structloc/localisation_core/localiser/localiser.hpp"

namespace structloc {
namespace {

using localisation_core::VisibilityCache;

world_model::VisibilityOptions HalfCircle() {
  return world_model::VisibilityOptions::Centred(geometry::kPi);
}

TEST(VisibilityCache, AnEntryHoldsWithinItsReachAndIsTheWorldModelsOwnVisibility) {
  const testing::OfficeScene office(geometry::kPi);
  VisibilityCache cache(office.world, office.scene, 0.25, 0.2, 4);
  EXPECT_TRUE(cache.SetView(HalfCircle()));
  EXPECT_FALSE(cache.SetView(HalfCircle()));
  const geometry::Pose2D at{19.5, 6.5, 0.2};
  const int entry = cache.Compute(at);
  world_model::Visibility direct;
  world_model::ComputeVisibility(office.world, office.scene, at, HalfCircle(), direct);
  ASSERT_EQ(cache.At(entry).walls.size(), direct.walls.size());
  for (size_t i = 0; i < direct.walls.size(); ++i) {
    EXPECT_EQ(cache.At(entry).walls[i].index, direct.walls[i].index);
    EXPECT_EQ(cache.At(entry).walls[i].first, direct.walls[i].first);
    EXPECT_EQ(cache.At(entry).walls[i].last, direct.walls[i].last);
  }
  EXPECT_EQ(cache.At(entry).corners, direct.corners);
  EXPECT_EQ(cache.At(entry).cylinders, direct.cylinders);
  EXPECT_TRUE(cache.Holds(entry, {19.7, 6.6, 0.3}));
  EXPECT_FALSE(cache.Holds(entry, {19.8, 6.5, 0.2}));   // 0.3 m away
  EXPECT_FALSE(cache.Holds(entry, {19.5, 6.5, 0.45}));  // turned 0.25 rad
  EXPECT_EQ(cache.Find({19.6, 6.5, 0.2}), entry);
  EXPECT_EQ(cache.Find({25.0, 6.5, 0.2}), -1);
  // The nearest of two that hold.
  const int other = cache.Compute({19.7, 6.5, 0.2});
  EXPECT_EQ(cache.Find({19.65, 6.5, 0.2}), other);
  EXPECT_EQ(cache.Find({19.52, 6.5, 0.2}), entry);
  // A full-circle view ignores the heading; a new view forgets every entry.
  EXPECT_TRUE(cache.SetView(world_model::VisibilityOptions{}));
  EXPECT_EQ(cache.Find({19.5, 6.5, 0.2}), -1);
  const int full = cache.Compute(at);
  EXPECT_TRUE(cache.Holds(full, {19.5, 6.5, 3.0}));
  EXPECT_EQ(cache.Computations(), 3u);
}

TEST(VisibilityCache, TheEntryInUseIsNeverReplaced) {
  const testing::OfficeScene office(geometry::kPi);
  VisibilityCache cache(office.world, office.scene, 0.25, 0.2, 2);
  cache.SetView(HalfCircle());
  const int kept = cache.Compute({2.0, 6.5, 0.0});
  for (int k = 1; k <= 5; ++k) {
    const int e = cache.Compute({2.0 + k, 6.5, 0.0}, kept);
    EXPECT_NE(e, kept);
  }
  EXPECT_TRUE(cache.Holds(kept, {2.0, 6.5, 0.0}));
  EXPECT_THROW(VisibilityCache(office.world, office.scene, 0.0, 0.2, 4), std::invalid_argument);
  EXPECT_THROW(VisibilityCache(office.world, office.scene, 0.25, 0.2, 1), std::invalid_argument);
}

// A robot driving along the corridor: only the first update computes a
// visibility; every later one is computed between scans (Anticipate).
TEST(VisibilityCache, AfterTheFirstScanUpdatesOnlyLookUp) {
  testing::OfficeScene office(4.71238898038469);
  localisation_core::Localiser localiser(office.world, office.options);
  std::mt19937 rng(3);
  uint64_t computed_in_updates = 0;
  for (int k = 0; k < 30; ++k) {
    office.truth = {2.0 + 0.1 * k, 6.5, 0.0};
    const uint64_t before = localiser.VisibilityComputations();
    const auto& r = localiser.Update(office.Input(office.Scan(541, rng)));
    if (k > 0) computed_in_updates += localiser.VisibilityComputations() - before;
    EXPECT_FALSE(r.lost) << k;
    localiser.Anticipate(r.pose);
  }
  EXPECT_EQ(computed_in_updates, 0u);
  // 2.9 m of driving at a visibility every 0.25 m.
  EXPECT_GE(localiser.VisibilityComputations(), 10u);
  EXPECT_LE(localiser.VisibilityComputations(), 14u);
}

}  // namespace
}  // namespace structloc
