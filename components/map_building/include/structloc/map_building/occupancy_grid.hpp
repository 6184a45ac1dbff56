// An occupancy grid as ROS holds one (nav_msgs/OccupancyGrid): cells of
// resolution_m metres, row 0 at the bottom (the grid origin), column 0 at the
// left, values -1 unknown, 0 free .. 100 occupied. The common currency of
// `structloc map import --grid`, `map export` and the log-odds grid builder.
// DDS-free.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

namespace structloc::map_building {

struct OccupancyGrid {
  static constexpr int8_t kUnknown = -1;
  static constexpr int8_t kFree = 0;
  static constexpr int8_t kOccupied = 100;

  double resolution_m = 0.05;
  // Pose of the lower-left corner of cell (0, 0) in the map frame: x, y (m)
  // and yaw (rad), as map_server's `origin`.
  Eigen::Vector3d origin{0.0, 0.0, 0.0};
  int width = 0;              // columns
  int height = 0;             // rows
  std::vector<int8_t> cells;  // width * height, row-major from the bottom row

  OccupancyGrid() = default;
  OccupancyGrid(int columns, int rows, double resolution, const Eigen::Vector3d& grid_origin,
                int8_t fill = kUnknown)
      : resolution_m(resolution),
        origin(grid_origin),
        width(columns),
        height(rows),
        cells(static_cast<size_t>(columns) * static_cast<size_t>(rows), fill) {}

  bool Contains(int column, int row) const {
    return column >= 0 && row >= 0 && column < width && row < height;
  }
  // Where cell (column, row) lies in `cells` (row-major from the bottom row).
  size_t Index(int column, int row) const {
    return static_cast<size_t>(row) * static_cast<size_t>(width) + static_cast<size_t>(column);
  }
  int8_t At(int column, int row) const { return cells[Index(column, row)]; }
  int8_t& At(int column, int row) { return cells[Index(column, row)]; }
  // Centre of a cell in the map frame.
  Eigen::Vector2d CellCentre(int column, int row) const;
  // The cell holding a map-frame point (may be outside the grid: check Contains).
  Eigen::Vector2i CellOf(const Eigen::Vector2d& p) const {
    const double c = std::cos(origin.z()), s = std::sin(origin.z());
    const double dx = p.x() - origin.x(), dy = p.y() - origin.y();
    return {static_cast<int>(std::floor((c * dx + s * dy) / resolution_m)),
            static_cast<int>(std::floor((-s * dx + c * dy) / resolution_m))};
  }
};

// Centres of many cells of one grid, its rotation's cosine and sine taken
// once (the same values as OccupancyGrid::CellCentre, which uses it).
class CellCentres {
 public:
  explicit CellCentres(const OccupancyGrid& grid)
      : grid_(grid), cos_(std::cos(grid.origin.z())), sin_(std::sin(grid.origin.z())) {}
  Eigen::Vector2d operator()(int column, int row) const {
    const double gx = (column + 0.5) * grid_.resolution_m;
    const double gy = (row + 0.5) * grid_.resolution_m;
    return {grid_.origin.x() + cos_ * gx - sin_ * gy, grid_.origin.y() + sin_ * gx + cos_ * gy};
  }

 private:
  const OccupancyGrid& grid_;
  double cos_, sin_;
};

inline Eigen::Vector2d OccupancyGrid::CellCentre(int column, int row) const {
  return CellCentres(*this)(column, row);
}

}  // namespace structloc::map_building
