// The global search's block bounds (CoarseBounds): on a random field, for
// random points and blocks of every level, a block's bound is at least the
// coarse score of every position in it, including points that fall off the
// field from some of the block's positions and not from others. A bound
// below one score would let the branch and bound drop the best candidate.
// Blocks bounded 2 x 2 at a time give the same bounds.
#include <gtest/gtest.h>

#include <random>

#include "structloc/localisation_core/global/coarse_bounds.hpp"
#include "structloc/localisation_core/global/lattice_gains.hpp"

namespace structloc {
namespace {

float Score(const std::vector<localisation_core::CoarseGain>& gain, int width, int height,
            int column, int row, const std::vector<int>& offsets) {
  uint32_t sum = 0;
  for (size_t i = 0; i + 1 < offsets.size(); i += 2) {
    const int c = column + offsets[i], r = row + offsets[i + 1];
    if (c >= 0 && r >= 0 && c < width && r < height)
      sum += gain[static_cast<size_t>(r) * width + c];
  }
  return static_cast<float>(sum);
}

// A level-`level` block's bound as the grid defines it (CoarseBounds::Grid),
// one block at a time.
float Bound(const localisation_core::CoarseBounds& bounds, int level, int column, int row,
            const int* offsets, size_t n) {
  const auto& grid = bounds.Grid(level);
  const int reach = bounds.Reach(level);
  uint32_t sum = 0;
  for (size_t i = 0; i < n; ++i) {
    const int c = column + reach + offsets[2 * i], r = row + reach + offsets[2 * i + 1];
    if (c >= 0 && r >= 0 && c < bounds.Columns(level) && r < bounds.Rows(level))
      sum += grid[static_cast<size_t>(r) * static_cast<size_t>(bounds.Columns(level)) +
                  static_cast<size_t>(c)];
  }
  return static_cast<float>(sum);
}

TEST(CoarseBounds, ABlocksBoundIsAtLeastTheScoreOfEachOfItsPositions) {
  constexpr int kWidth = 53, kHeight = 41, kStep = 3, kLevels = 3;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<localisation_core::CoarseGain> gain(static_cast<size_t>(kWidth) * kHeight);
  for (auto& g : gain)  // sparse, like walls
    g = localisation_core::ToCoarseGain(unit(rng) < 0.9f ? 0.0f : unit(rng));
  const localisation_core::CoarseBounds bounds(gain, kWidth, kHeight, kStep, kLevels);
  ASSERT_EQ(bounds.Levels(), kLevels);
  std::uniform_int_distribution<int> offset(-70, 70), start(-30, 60);
  int tight = 0, checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<int> offsets(2 * 20);
    for (auto& o : offsets) o = offset(rng);
    const int level = 1 + trial % kLevels, side = 1 << level;
    const int column = start(rng), row = start(rng);
    const float bound = Bound(bounds, level, column, row, offsets.data(), offsets.size() / 2);
    float best = 0.0f;
    for (int j = 0; j < side; ++j) {
      for (int i = 0; i < side; ++i) {
        const float score =
            Score(gain, kWidth, kHeight, column + i * kStep, row + j * kStep, offsets);
        ASSERT_LE(score, bound) << "level " << level << " block at " << column << ", " << row
                                << ": position " << i << ", " << j;
        best = std::max(best, score);
        ++checked;
      }
    }
    if (bound == best) ++tight;
  }
  EXPECT_GT(checked, 1000);
  // The bound is not just large: with nothing to bound (all points off the
  // field) it is 0, and sometimes it is met by the block's best position.
  const std::vector<int> far_away = {1000, 1000, -1000, 5};
  EXPECT_EQ(Bound(bounds, 2, 0, 0, far_away.data(), 2), 0.0f);
  EXPECT_GT(tight, 0);
}

// The global search bounds blocks of a level 2 x 2 at a time from that
// level's grid laid out by phase, as GlobalLocaliser builds it (the quarters
// of a level-2 block at level 1, the top-level blocks at level 2): the same
// bounds as the grid, one block at a time.
TEST(CoarseBounds, BlocksBoundTogetherAreBoundAsOneByOne) {
  constexpr int kWidth = 61, kHeight = 44, kStep = 5, kLevels = 2;
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<localisation_core::CoarseGain> gain(static_cast<size_t>(kWidth) * kHeight);
  for (auto& g : gain) g = localisation_core::ToCoarseGain(unit(rng) < 0.9f ? 0.0f : unit(rng));
  const localisation_core::CoarseBounds bounds(gain, kWidth, kHeight, kStep, kLevels);
  const int first_column = 2, first_row = 3;  // the lattice's first position's cell
  std::uniform_int_distribution<int> offset(-70, 70), block(-2, 4);
  for (int level = 1; level <= kLevels; ++level) {
    const int side = 1 << level;  // lattice steps between the level's blocks
    const int reach = bounds.Reach(level);
    const localisation_core::LatticeGains blocks(bounds.Grid(level), bounds.Columns(level),
                                                 bounds.Rows(level), side * kStep,
                                                 first_column + reach, first_row + reach);
    for (int trial = 0; trial < 100; ++trial) {
      std::vector<int> offsets(2 * 20);
      for (auto& o : offsets) o = offset(rng);
      const int i = block(rng), j = block(rng);  // in blocks of the level
      uint32_t sums[4] = {0, 0, 0, 0};
      for (size_t p = 0; p + 1 < offsets.size(); p += 2)
        blocks.AddBlock(blocks.Prepare(offsets[p], offsets[p + 1]), i, j, sums);
      for (int q = 0; q < 4; ++q) {
        const int column = first_column + kStep * side * (i + q % 2);
        const int row = first_row + kStep * side * (j + q / 2);
        EXPECT_EQ(static_cast<float>(sums[q]),
                  Bound(bounds, level, column, row, offsets.data(), offsets.size() / 2))
            << "level " << level << ", block " << i + q % 2 << ", " << j + q / 2;
      }
    }
  }
}

}  // namespace
}  // namespace structloc
