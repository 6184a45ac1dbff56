// Which wall (or pillar surface) of a map a point lies on: a uniform grid of
// buckets over the map, each listing the walls and pillars passing near it, so
// that checking a million readings against a thousand walls stays fast.
// DDS-free.
#pragma once

#include <Eigen/Core>
#include <unordered_map>
#include <vector>

#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

struct NearestSurface {
  enum class Kind { kNone, kWall, kPillar };
  Kind kind = Kind::kNone;
  size_t index = 0;       // into world.Walls() or world.Cylinders()
  double distance_m = 0;  // from the point to the wall segment or the pillar's surface
};

class NearestWallIndex {
 public:
  // Finds surfaces within `reach_m` of a point; `bucket_m` is the bucket size.
  NearestWallIndex(const world_model::WorldModel& world, double reach_m, double bucket_m = 0.5);
  // The nearest wall or pillar surface within reach of `p`, else kind kNone.
  NearestSurface Nearest(const Eigen::Vector2d& p) const;

 private:
  long long Key(long long ix, long long iy) const { return ix * 4000037LL + iy; }
  void Register(size_t entry, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi);
  const world_model::WorldModel& world_;
  double reach_m_;
  double bucket_m_;
  std::unordered_map<long long, std::vector<size_t>> buckets_;  // entries: walls, then pillars
};

// Distance from p to the segment a-b.
double PointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b);

}  // namespace structloc::map_building
