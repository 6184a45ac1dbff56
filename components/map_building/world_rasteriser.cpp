// A world model drawn into an occupancy grid for AMCL / Nav2 (see header).
#include "structloc/map_building/world_rasteriser.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace structloc::map_building {
namespace {

constexpr double kEpsilonCells = 1e-6;

// A map-frame point in grid units: cell (i, j) spans [i, i+1) x [j, j+1).
Eigen::Vector2d ToGrid(const map_building::OccupancyGrid& grid, const Eigen::Vector2d& p) {
  const double c = std::cos(grid.origin.z()), s = std::sin(grid.origin.z());
  const double dx = p.x() - grid.origin.x(), dy = p.y() - grid.origin.y();
  return Eigen::Vector2d(c * dx + s * dy, -s * dx + c * dy) / grid.resolution_m;
}

void Occupy(map_building::OccupancyGrid& grid, int column, int row) {
  if (grid.Contains(column, row)) grid.At(column, row) = map_building::OccupancyGrid::kOccupied;
}

}  // namespace

void MarkSegment(map_building::OccupancyGrid& grid, const Eigen::Vector2d& a,
                 const Eigen::Vector2d& b) {
  const Eigen::Vector2d ga = ToGrid(grid, a), gb = ToGrid(grid, b);
  const Eigen::Vector2d d = gb - ga;
  const int first = static_cast<int>(std::floor(std::min(ga.x(), gb.x()) - kEpsilonCells));
  const int last = static_cast<int>(std::floor(std::max(ga.x(), gb.x()) + kEpsilonCells));
  for (int column = std::max(first, -1); column <= std::min(last, grid.width); ++column) {
    double t0 = 0.0, t1 = 1.0;
    if (d.x() != 0.0) {
      const double ta = (column - kEpsilonCells - ga.x()) / d.x();
      const double tb = (column + 1 + kEpsilonCells - ga.x()) / d.x();
      t0 = std::max(0.0, std::min(ta, tb));
      t1 = std::min(1.0, std::max(ta, tb));
      if (t0 > t1) continue;
    }
    const double v0 = ga.y() + t0 * d.y(), v1 = ga.y() + t1 * d.y();
    const int bottom = static_cast<int>(std::floor(std::min(v0, v1) - kEpsilonCells));
    const int top = static_cast<int>(std::floor(std::max(v0, v1) + kEpsilonCells));
    for (int row = std::max(bottom, 0); row <= std::min(top, grid.height - 1); ++row)
      Occupy(grid, column, row);
  }
}

void MarkCircle(map_building::OccupancyGrid& grid, const Eigen::Vector2d& centre, double radius) {
  const Eigen::Vector2d g = ToGrid(grid, centre);
  const double r = radius / grid.resolution_m;
  const int c0 = std::max(0, static_cast<int>(std::floor(g.x() - r)) - 1);
  const int c1 = std::min(grid.width - 1, static_cast<int>(std::floor(g.x() + r)) + 1);
  const int r0 = std::max(0, static_cast<int>(std::floor(g.y() - r)) - 1);
  const int r1 = std::min(grid.height - 1, static_cast<int>(std::floor(g.y() + r)) + 1);
  for (int row = r0; row <= r1; ++row) {
    for (int column = c0; column <= c1; ++column) {
      const double nx = std::clamp(g.x(), double(column), column + 1.0) - g.x();
      const double ny = std::clamp(g.y(), double(row), row + 1.0) - g.y();
      const double fx = std::max(std::abs(column - g.x()), std::abs(column + 1.0 - g.x()));
      const double fy = std::max(std::abs(row - g.y()), std::abs(row + 1.0 - g.y()));
      const double nearest = std::hypot(nx, ny), farthest = std::hypot(fx, fy);
      auto& cell = grid.At(column, row);
      if (nearest <= r + kEpsilonCells && farthest >= r - kEpsilonCells) {
        cell = map_building::OccupancyGrid::kOccupied;
      } else if (farthest < r && cell != map_building::OccupancyGrid::kOccupied) {
        cell = map_building::OccupancyGrid::kUnknown;
      }
    }
  }
}

map_building::OccupancyGrid RasteriseWorld(const world_model::WorldModel& world,
                                           const RasteriseOptions& options) {
  if (!(options.resolution_m > 0.0) || !std::isfinite(options.resolution_m))
    throw std::invalid_argument("the grid resolution must be a positive number of metres");
  if (!(options.margin_m >= 0.0) || !std::isfinite(options.margin_m))
    throw std::invalid_argument("the grid margin must be zero or a positive number of metres");
  const Eigen::Vector4d bounds = world.Bounds();
  const double res = options.resolution_m;
  const double x0 = std::floor((bounds[0] - options.margin_m) / res) * res;
  const double y0 = std::floor((bounds[1] - options.margin_m) / res) * res;
  const double columns = std::ceil((bounds[2] + options.margin_m - x0) / res);
  const double rows = std::ceil((bounds[3] + options.margin_m - y0) / res);
  if (columns * rows > static_cast<double>(options.max_cells) || columns > 1e9 || rows > 1e9)
    throw std::invalid_argument(
        "a grid of " + std::to_string(static_cast<long long>(columns)) + " x " +
        std::to_string(static_cast<long long>(rows)) + " cells is beyond the limit of " +
        std::to_string(options.max_cells) + " cells: choose a coarser resolution");
  map_building::OccupancyGrid grid(std::max(1, static_cast<int>(columns)),
                                   std::max(1, static_cast<int>(rows)), res, {x0, y0, 0.0},
                                   map_building::OccupancyGrid::kFree);
  for (const auto& wall : world.Walls()) MarkSegment(grid, wall.a, wall.b);
  for (const auto& cylinder : world.Cylinders()) MarkCircle(grid, cylinder.centre, cylinder.radius);
  return grid;
}

}  // namespace structloc::map_building
