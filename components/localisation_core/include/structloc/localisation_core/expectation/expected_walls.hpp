// Where the world model and the odometric sensor pose say walls should appear
// in the scan (thesis 3.5.3 EQ 23-24), computed once per update for the
// visible walls only, so the clustering hot loops compare against precomputed
// numbers. Every feature kind may read them (the corners' redundancy rule
// does); each point kind places its own points (expected_points.hpp).
#pragma once

#include <algorithm>
#include <cassert>
#include <stdexcept>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/world_model/visibility.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::localisation_core {

// Collinear walls (same r, alpha within tolerance) give one constraint: they
// are grouped into one wall line with the id of its first wall.
struct WallLineModel {
  geometry::Line line;
  std::vector<int> walls;  // indices into WorldModel::Walls()
  int model_id = 0;
  double c = 1.0, s = 0.0;  // cos and sin of line.alpha, computed once
};
std::vector<WallLineModel> GroupCollinearWalls(const world_model::WorldModel& world,
                                               double r_tolerance_m = 0.01,
                                               double alpha_tolerance_rad = 0.01);

// An expected wall in the sensor frame, oriented like the world line's normal:
// alpha = alpha_W - theta, r = r_W - (x cos alpha_W + y sin alpha_W) (may be < 0).
struct ExpectedWall {
  int line_index = 0;
  int model_id = 0;
  int slot = 0;                  // the line's slot in the MapErrorMemory
  double map_error_scale = 1.0;  // factor on the map's share of a pairing's covariance
  double r = 0.0;
  double c = 1.0;  // cos/sin of alpha (sensor frame)
  double s = 0.0;
  geometry::Line world;
  double world_c = 1.0;  // cos/sin of the world line's alpha
  double world_s = 0.0;
};

// The visible part of one map wall on an expected wall line, along the world
// line direction (-sin, cos): a scan segment pairs with a line only where it
// overlaps one of these, not across a doorway between two of them.
struct ExpectedExtent {
  int expected_index = 0;  // into ExpectedWalls::walls
  double lo = 0.0, hi = 0.0;
  double wall_centre = 0.0;  // centre of the whole map wall (its errors pivot there)
  double wall_half_length = 0.0;
};

struct ExpectedWalls {
  std::vector<ExpectedWall> walls;
  std::vector<ExpectedExtent> extents;  // one per visible map wall; by wall after IndexExtents
  void Reserve(size_t lines, size_t walls);
  // Orders the extents by expected wall (keeping their order within a wall)
  // and indexes them, so that DistanceOutside reads only the wall's own; call
  // once walls and extents are filled.
  void IndexExtents();
  // The extent of expected wall `e` nearest to `t` (along its world line):
  // the distance outside it (0 inside) and, through `wall`, that extent.
  // Inline: the wall gate asks it for every window line. Call IndexExtents
  // first (and again after changing walls or extents).
  double DistanceOutside(int e, double t, const ExpectedExtent** wall = nullptr) const {
    if (first_extent_.empty()) {
      throw std::logic_error("ExpectedWalls::DistanceOutside before IndexExtents");
    }
    assert(first_extent_.size() == walls.size() + 1 &&
           static_cast<size_t>(first_extent_.back()) == extents.size());  // not stale
    double best = 1e300;
    const auto begin = extents.begin() + first_extent_[static_cast<size_t>(e)];
    const auto end = extents.begin() + first_extent_[static_cast<size_t>(e) + 1];
    for (auto it = begin; it != end; ++it) {
      const double d = std::max({it->lo - t, t - it->hi, 0.0});
      if (d < best) {
        best = d;
        if (wall != nullptr) *wall = &*it;
      }
    }
    return best;
  }

 private:
  std::vector<int> first_extent_;  // of wall e; walls.size() + 1 entries
  std::vector<int> next_;          // IndexExtents' scratch
  std::vector<ExpectedExtent> sorted_;
};

// `wall_line_of` maps a wall index to its WallLineModel index. An expected
// wall's slot in the MapErrorMemory is its line's index: the wall lines take
// the first slots, the point kinds theirs after them.
void ComputeExpectedWalls(const world_model::WorldModel& world,
                          const std::vector<WallLineModel>& lines,
                          const std::vector<int>& wall_line_of,
                          const world_model::Visibility& visibility,
                          const geometry::Pose2D& sensor_pose, ExpectedWalls& out);

}  // namespace structloc::localisation_core
