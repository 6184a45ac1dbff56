// Upper bounds of the global search's coarse score over square blocks of
// lattice positions, so that the search can skip whole blocks (and headings)
// that cannot hold one of the best candidates: branch and bound as in Olson's
// multi-resolution correlative scan matching and Cartographer's fast
// correlative matcher, here exact for the candidates the search keeps. Level
// L covers blocks of 2^L x 2^L lattice positions; its grid holds, per cell,
// the largest coarse gain in the square of cells that a point looked up from
// any position of the block can fall into. Gains are held as 16-bit counts
// of 1/65535 (CoarseGain): half the memory of floats (the coarse phase took
// about 4 % less time in the pillared hall), and their sums are exact, so
// hits that tie do so whatever order their points were added in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace structloc::localisation_core {

// A gain in [0, 1] as a count of 1/65535.
using CoarseGain = uint16_t;
CoarseGain ToCoarseGain(double gain);

class CoarseBounds {
 public:
  // Levels 1..levels over `gain` (width x height cells, row major), for
  // lattice positions `step_cells` whole cells apart.
  CoarseBounds(const std::vector<CoarseGain>& gain, int width, int height, int step_cells,
               int levels);
  CoarseBounds() = default;

  int Levels() const { return static_cast<int>(grids_.size()); }
  // Level `level`'s grid (row major, Columns(level) x Rows(level) cells): a
  // block whose first (lowest x and y) position lies in cell (c, r) of the
  // field looks a point o cells away up in cell (c + o + Reach(level), ...)
  // of it. The sum of those cells over a scan's points (off the grid
  // nothing) is at least the coarse score (the sum of the gains, in counts,
  // of the cells the points fall into) of every position of the block.
  const std::vector<CoarseGain>& Grid(int level) const {
    return grids_[static_cast<size_t>(level - 1)];
  }
  int Reach(int level) const { return reach_[static_cast<size_t>(level - 1)]; }
  int Columns(int level) const { return width_ + Reach(level); }
  int Rows(int level) const { return height_ + Reach(level); }

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::vector<CoarseGain>> grids_;  // level L at L - 1
  std::vector<int> reach_;                      // level L's square: reach_[L - 1] + 1 cells a side
};

}  // namespace structloc::localisation_core
