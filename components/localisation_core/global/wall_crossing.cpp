// Beam tracing on a distance field (see header).
#include "structloc/localisation_core/global/wall_crossing.hpp"

namespace structloc::localisation_core {

bool CrossesWall(const WallDistanceField& field, const Eigen::Vector2d& from,
                 const Eigen::Vector2d& to) {
  const double res = field.resolution_m;
  const double length = (to - from).norm();
  const int steps = static_cast<int>(length / (0.5 * res));
  if (steps < 2) return false;
  // Samples per cell: the loop multiplies by it, as each next sample waits
  // on this one's skip (a division there would lengthen every step).
  const double samples_per_cell = steps / length * res;
  // In cells: the start, and the step from one sample to the next.
  const double fx = (from.x() - field.x0) / res, fy = (from.y() - field.y0) / res;
  const double dx = (to.x() - from.x()) / (res * steps), dy = (to.y() - from.y()) / (res * steps);
  // A wall cell's points lie at least (d - sqrt 2) cells from any point of a
  // cell whose centre is d cells from the wall cell's centre (with a margin
  // for the field's rounding): the samples that near are clear.
  constexpr double kCellDiagonal = 1.4142135623730951 + 1e-3;
  const double width = field.width, height = field.height;
  const std::vector<uint8_t>& cells = *field.cells;
  for (int i = 1; i < steps;) {
    const double x = fx + dx * i, y = fy + dy * i;
    if (!(x >= 0.0 && y >= 0.0 && x < width && y < height)) return false;
    const double d =
        cells[static_cast<size_t>(static_cast<int>(y)) * field.width + static_cast<int>(x)];
    if (d == 0.0) return true;
    const double clear_samples = (d - kCellDiagonal) * samples_per_cell;
    i += 1 + (clear_samples > 1.0 ? static_cast<int>(clear_samples) : 0);
  }
  return false;
}

}  // namespace structloc::localisation_core
