// Dropping shadow walls (see header).
#include "structloc/map_building/shadow_walls.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace structloc::map_building {
namespace {

// Whether `shorter` lies alongside `longer` as its shadow.
bool IsShadow(const FittedWall& longer, const FittedWall& shorter, const ShadowWallOptions& o) {
  const double length = longer.Length(), own = shorter.Length();
  if (length <= 0.0 || own <= 0.0) return false;
  const Eigen::Vector2d u = (longer.b - longer.a) / length;
  const Eigen::Vector2d v = (shorter.b - shorter.a) / own;
  if (std::abs(u.x() * v.y() - u.y() * v.x()) > std::sin(o.max_angle_rad)) return false;
  const Eigen::Vector2d n(-u.y(), u.x());
  if (std::abs(n.dot(shorter.a - longer.a)) > o.max_offset_m ||
      std::abs(n.dot(shorter.b - longer.a)) > o.max_offset_m) {
    return false;
  }
  // Two faces of one partition are seen from opposite sides; a shadow from the
  // same side as its wall.
  const double side_longer = n.dot(longer.viewpoint - longer.a);
  const double side_shorter = n.dot(shorter.viewpoint - longer.a);
  if (side_longer * side_shorter < 0.0) return false;
  const double t1 = u.dot(shorter.a - longer.a), t2 = u.dot(shorter.b - longer.a);
  const double overlap = std::min(length, std::max(t1, t2)) - std::max(0.0, std::min(t1, t2));
  return overlap >= o.min_overlap * own;
}

}  // namespace

size_t DropShadowWalls(std::vector<FittedWall>& walls, const ShadowWallOptions& options) {
  if (options.max_offset_m <= 0.0) return 0;
  std::vector<size_t> order(walls.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&walls](size_t a, size_t b) { return walls[a].Length() > walls[b].Length(); });
  std::vector<bool> shadow(walls.size(), false);
  for (size_t i = 0; i < order.size(); ++i) {
    if (shadow[order[i]]) continue;
    for (size_t j = i + 1; j < order.size(); ++j) {
      if (!shadow[order[j]] && IsShadow(walls[order[i]], walls[order[j]], options))
        shadow[order[j]] = true;
    }
  }
  size_t dropped = 0, kept = 0;
  for (size_t k = 0; k < walls.size(); ++k) {
    if (shadow[k]) {
      ++dropped;
    } else {
      walls[kept++] = walls[k];
    }
  }
  walls.resize(kept);
  return dropped;
}

}  // namespace structloc::map_building
