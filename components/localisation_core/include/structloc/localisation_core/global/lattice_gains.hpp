// The global search's blurred field (or a grid of its bounds) laid out for
// its lattice of positions (or of blocks), so that a block of 2 x 2
// positions is scored (or a block's four quarters bounded) with two short
// loads a point instead of four scattered ones. Positions lie a whole
// number of cells (`step`) apart; a point a given offset from each of them
// falls into cells with the same column and row modulo `step` (the same
// phase), one step apart. Phase (mx, my) keeps those cells of the field side by side, one per
// lattice step, so that the cells a point falls into from neighbouring
// positions are neighbours in memory. Same gains, same sums (integer counts):
// only the layout differs from the field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "structloc/localisation_core/global/coarse_bounds.hpp"

namespace structloc::localisation_core {

class LatticeGains {
 public:
  // `gain`: width x height cells, row major; the lattice's first position
  // lies in cell (first_column, first_row) and the others `step_cells` whole
  // cells apart.
  LatticeGains(const std::vector<CoarseGain>& gain, int width, int height, int step_cells,
               int first_column, int first_row);
  LatticeGains() = default;

  // Where the point `column`, `row` cells from a position's cell falls, from
  // the lattice's first position: its phase and whole steps.
  struct Offset {
    int phase = 0;
    int steps_x = 0, steps_y = 0;
  };
  Offset Prepare(int column, int row) const;

  // Adds to sums[0..3] the gains of the cells a point `offset` from lattice
  // positions (i, j), (i + 1, j), (i, j + 1) and (i + 1, j + 1) falls into
  // (nothing off the field).
  void AddBlock(const Offset& offset, int i, int j, uint32_t sums[4]) const {
    const int u = offset.steps_x + i, v = offset.steps_y + j;
    // With one column and row of zeros around each phase, both columns
    // (rows) of the block lie in the stored ones from -1 to columns_ - 1.
    if (u < -1 || u >= columns_ || v < -1 || v >= rows_) return;
    const CoarseGain* near =
        &phases_[static_cast<size_t>(offset.phase)]
                [static_cast<size_t>(v + 1) * stride_ + static_cast<size_t>(u + 1)];
    const CoarseGain* far = near + stride_;
    sums[0] += near[0];
    sums[1] += near[1];
    sums[2] += far[0];
    sums[3] += far[1];
  }

 private:
  int step_ = 1;
  int lattice_column_ = 0, lattice_row_ = 0;     // the lattice's first position's cell
  int origin_column_ = 0, origin_row_ = 0;       // the cell at column 0, row 0 of phase 0
  int columns_ = 0, rows_ = 0;                   // of each phase, without the border of zeros
  size_t stride_ = 0;                            // columns_ + 2
  std::vector<std::vector<CoarseGain>> phases_;  // phase my * step + mx
};

}  // namespace structloc::localisation_core
