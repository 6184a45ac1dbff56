// The blurred field by lattice phase (see header).
#include "structloc/localisation_core/global/lattice_gains.hpp"

#include <stdexcept>
#include <string>

namespace structloc::localisation_core {

namespace {

// Floor division and the non-negative remainder.
int FloorDiv(int a, int b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}
int Mod(int a, int b) {
  return a - b * FloorDiv(a, b);
}

}  // namespace

LatticeGains::LatticeGains(const std::vector<CoarseGain>& gain, int width, int height,
                           int step_cells, int first_column, int first_row)
    : step_(step_cells), lattice_column_(first_column), lattice_row_(first_row) {
  if (step_cells < 1 || width < 0 || height < 0 ||
      gain.size() != static_cast<size_t>(width) * static_cast<size_t>(height))
    throw std::invalid_argument("lattice gains: a field of " + std::to_string(gain.size()) +
                                " cells is not " + std::to_string(width) + " x " +
                                std::to_string(height) + ", or the step is below one cell");
  // Phase (mx, my), column u, row v holds cell (origin_column + mx + step u,
  // origin_row + my + step v): the origin is the lattice's first position's
  // cell moved by whole steps to the field's first column and row (or just
  // before them).
  origin_column_ = first_column + step_ * FloorDiv(-first_column, step_);
  origin_row_ = first_row + step_ * FloorDiv(-first_row, step_);
  columns_ = FloorDiv(width - 1 - origin_column_, step_) + 1;
  rows_ = FloorDiv(height - 1 - origin_row_, step_) + 1;
  stride_ = static_cast<size_t>(columns_) + 2;
  phases_.assign(static_cast<size_t>(step_) * static_cast<size_t>(step_),
                 std::vector<CoarseGain>(stride_ * (static_cast<size_t>(rows_) + 2), 0));
  for (int my = 0; my < step_; ++my) {
    for (int mx = 0; mx < step_; ++mx) {
      auto& phase = phases_[static_cast<size_t>(my * step_ + mx)];
      for (int v = 0; v < rows_; ++v) {
        const int r = origin_row_ + my + step_ * v;
        if (r < 0 || r >= height) continue;
        for (int u = 0; u < columns_; ++u) {
          const int c = origin_column_ + mx + step_ * u;
          if (c < 0 || c >= width) continue;
          phase[static_cast<size_t>(v + 1) * stride_ + static_cast<size_t>(u + 1)] =
              gain[static_cast<size_t>(r) * static_cast<size_t>(width) + static_cast<size_t>(c)];
        }
      }
    }
  }
}

LatticeGains::Offset LatticeGains::Prepare(int column, int row) const {
  const int c = lattice_column_ - origin_column_ + column;
  const int r = lattice_row_ - origin_row_ + row;
  return {Mod(r, step_) * step_ + Mod(c, step_), FloorDiv(c, step_), FloorDiv(r, step_)};
}

}  // namespace structloc::localisation_core
