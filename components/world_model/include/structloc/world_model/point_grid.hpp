// A uniform hash grid over 2-D points: "which stored points lie near p" in
// constant time per query, so that deriving corners from wall ends does not
// try every pair of walls (a map of 100 000 walls loads in a fraction of a
// second instead of a minute). DDS-free.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace structloc::world_model {

class PointGrid {
 public:
  // Points closer than `cell_size_m` to a query are always found by ForEachNear.
  // Coordinates must be finite and bounded (WorldLimits) so cell indices fit.
  explicit PointGrid(double cell_size_m) : cell_size_m_(cell_size_m) {}

  void Insert(const Eigen::Vector2d& point, size_t payload) {
    cells_[Key(Cell(point.x()), Cell(point.y()))].push_back(payload);
  }

  // Calls visit(payload) for every point in the 3x3 cells around `point`: a
  // superset of the points within cell_size_m; the caller checks the distance.
  template <class Visit>
  void ForEachNear(const Eigen::Vector2d& point, Visit visit) const {
    const int64_t cx = Cell(point.x()), cy = Cell(point.y());
    for (int64_t dx = -1; dx <= 1; ++dx) {
      for (int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(Key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (const size_t payload : it->second) visit(payload);
      }
    }
  }

 private:
  int64_t Cell(double coordinate) const {
    return static_cast<int64_t>(std::floor(coordinate / cell_size_m_));
  }
  static int64_t Key(int64_t cx, int64_t cy) {
    return static_cast<int64_t>((static_cast<uint64_t>(cx) << 32) ^
                                (static_cast<uint64_t>(cy) & 0xffffffffULL));
  }

  double cell_size_m_;
  std::unordered_map<int64_t, std::vector<size_t>> cells_;
};

}  // namespace structloc::world_model
