// The blurred field laid out by lattice phase (LatticeGains): on a random
// field, for random points and 2 x 2 blocks of lattice positions, the sums
// AddBlock gives are those of looking each point's cell up in the field
// (nothing off it), also where the block or its points hang over the field's
// edges. A wrong sum would change the global search's candidates.
#include <gtest/gtest.h>

#include <random>

#include "structloc/localisation_core/global/lattice_gains.hpp"

namespace structloc {
namespace {

using localisation_core::CoarseGain;
using localisation_core::LatticeGains;

uint32_t Sum(const std::vector<CoarseGain>& gain, int width, int height, int column, int row,
             const std::vector<int>& offsets) {
  uint32_t sum = 0;
  for (size_t i = 0; i + 1 < offsets.size(); i += 2) {
    const int c = column + offsets[i], r = row + offsets[i + 1];
    if (c >= 0 && r >= 0 && c < width && r < height)
      sum += gain[static_cast<size_t>(r) * width + c];
  }
  return sum;
}

TEST(LatticeGains, ABlocksSumsAreThoseOfLookingEachCellUp) {
  constexpr int kWidth = 47, kHeight = 38, kStep = 5;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> any_gain(0, 65535), offset(-60, 60), first(-3, 7);
  for (int field = 0; field < 4; ++field) {
    std::vector<CoarseGain> gain(static_cast<size_t>(kWidth) * kHeight);
    for (auto& g : gain) g = static_cast<CoarseGain>(any_gain(rng));
    // The lattice's first position may lie off the field (its first cell
    // before the field's) or inside it.
    const int first_column = first(rng), first_row = first(rng);
    const LatticeGains lattice(gain, kWidth, kHeight, kStep, first_column, first_row);
    std::uniform_int_distribution<int> block(-4, 12);
    for (int trial = 0; trial < 200; ++trial) {
      std::vector<int> offsets(2 * 30);
      for (auto& o : offsets) o = offset(rng);
      const int i = block(rng), j = block(rng);
      uint32_t sums[4] = {0, 0, 0, 0};
      for (size_t p = 0; p + 1 < offsets.size(); p += 2)
        lattice.AddBlock(lattice.Prepare(offsets[p], offsets[p + 1]), i, j, sums);
      for (int q = 0; q < 4; ++q) {
        const int column = first_column + kStep * (i + q % 2);
        const int row = first_row + kStep * (j + q / 2);
        EXPECT_EQ(sums[q], Sum(gain, kWidth, kHeight, column, row, offsets))
            << "field " << field << ", block " << i << ", " << j << ", position " << q;
      }
    }
  }
}

TEST(LatticeGains, RefusesAFieldOfTheWrongSize) {
  EXPECT_THROW(LatticeGains(std::vector<CoarseGain>(10), 4, 3, 5, 0, 0), std::invalid_argument);
  EXPECT_THROW(LatticeGains(std::vector<CoarseGain>(12), 4, 3, 0, 0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace structloc
