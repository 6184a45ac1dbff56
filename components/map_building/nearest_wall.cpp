// Nearest wall or pillar surface of a map (see header).
#include "structloc/map_building/nearest_wall.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace structloc::map_building {

double PointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp(d.dot(p - a) / l2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

NearestWallIndex::NearestWallIndex(const world_model::WorldModel& world, double reach_m,
                                   double bucket_m)
    : world_(world), reach_m_(reach_m), bucket_m_(bucket_m) {
  if (!(reach_m > 0.0) || !(bucket_m > 0.0))
    throw std::invalid_argument("NearestWallIndex: reach and bucket size must be > 0");
  const Eigen::Vector2d pad(reach_m, reach_m);
  const auto& walls = world.Walls();
  for (size_t i = 0; i < walls.size(); ++i) {
    const Eigen::Vector2d lo = walls[i].a.cwiseMin(walls[i].b) - pad;
    const Eigen::Vector2d hi = walls[i].a.cwiseMax(walls[i].b) + pad;
    Register(i, lo, hi);
  }
  const auto& pillars = world.Cylinders();
  for (size_t i = 0; i < pillars.size(); ++i) {
    const Eigen::Vector2d r(pillars[i].radius, pillars[i].radius);
    Register(walls.size() + i, pillars[i].centre - r - pad, pillars[i].centre + r + pad);
  }
}

void NearestWallIndex::Register(size_t entry, const Eigen::Vector2d& lo,
                                const Eigen::Vector2d& hi) {
  const auto x0 = static_cast<long long>(std::floor(lo.x() / bucket_m_));
  const auto x1 = static_cast<long long>(std::floor(hi.x() / bucket_m_));
  const auto y0 = static_cast<long long>(std::floor(lo.y() / bucket_m_));
  const auto y1 = static_cast<long long>(std::floor(hi.y() / bucket_m_));
  for (long long ix = x0; ix <= x1; ++ix) {
    for (long long iy = y0; iy <= y1; ++iy) buckets_[Key(ix, iy)].push_back(entry);
  }
}

NearestSurface NearestWallIndex::Nearest(const Eigen::Vector2d& p) const {
  NearestSurface best;
  const auto key = Key(static_cast<long long>(std::floor(p.x() / bucket_m_)),
                       static_cast<long long>(std::floor(p.y() / bucket_m_)));
  const auto found = buckets_.find(key);
  if (found == buckets_.end()) return best;
  best.distance_m = reach_m_;
  const auto& walls = world_.Walls();
  for (const size_t entry : found->second) {
    double d = 0.0;
    if (entry < walls.size()) {
      d = PointSegmentDistance(p, walls[entry].a, walls[entry].b);
    } else {
      const auto& c = world_.Cylinders()[entry - walls.size()];
      d = std::abs((p - c.centre).norm() - c.radius);
    }
    if (d > best.distance_m) continue;
    best.distance_m = d;
    best.kind = entry < walls.size() ? NearestSurface::Kind::kWall : NearestSurface::Kind::kPillar;
    best.index = entry < walls.size() ? entry : entry - walls.size();
  }
  if (best.kind == NearestSurface::Kind::kNone) best.distance_m = 0.0;
  return best;
}

}  // namespace structloc::map_building
