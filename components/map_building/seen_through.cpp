// Scans that looked through a pillar's place (see header). Most scans'
// points sweep in bearing, so the few in a pillar's narrow cone are found by
// bisection; scans that do not are walked whole.
#include "structloc/map_building/seen_through.hpp"

#include <algorithm>
#include <cmath>

namespace structloc::map_building {
namespace {

double Bearing(const Eigen::Vector2d& p) {
  return std::atan2(p.y(), p.x());
}

// Whether every point of `points` with a bearing in [lo, hi] (lo <= hi,
// within [-pi, pi]) lies beyond `beyond` metres; counts them in `in_cone`.
bool AllBeyond(const std::vector<Eigen::Vector2d>& points, bool sweeps, double lo, double hi,
               double beyond, size_t& in_cone) {
  size_t first = 0, last = points.size();
  if (sweeps) {
    first = static_cast<size_t>(
        std::partition_point(points.begin(), points.end(),
                             [lo](const Eigen::Vector2d& p) { return Bearing(p) < lo; }) -
        points.begin());
    last = static_cast<size_t>(
        std::partition_point(points.begin() + static_cast<long>(first), points.end(),
                             [hi](const Eigen::Vector2d& p) { return Bearing(p) <= hi; }) -
        points.begin());
  }
  for (size_t i = first; i < last; ++i) {
    const double b = Bearing(points[i]);
    if (b < lo || b > hi) continue;
    if (points[i].squaredNorm() <= beyond * beyond) return false;
    ++in_cone;
  }
  return true;
}

}  // namespace

SeeThroughCheck::SeeThroughCheck(const std::vector<PosedScan>& scans) {
  scans_.reserve(scans.size());
  for (const auto& scan : scans) {
    Scan s{&scan, geometry::Inverse(scan.laser_pose), 0.0, true};
    double previous = -geometry::kPi - 1.0;
    for (const auto& p : scan.points) {
      s.farthest_m = std::max(s.farthest_m, p.norm());
      const double b = Bearing(p);
      s.sweeps = s.sweeps && b >= previous;
      previous = b;
    }
    scans_.push_back(s);
  }
}

size_t SeeThroughCheck::ScansSeeingThrough(const world_model::Cylinder& pillar,
                                           double margin_m) const {
  size_t through = 0;
  for (const auto& s : scans_) {
    const Eigen::Vector2d centre = s.from_map.Apply(pillar.centre);
    const double d = centre.norm();
    const double beyond = d + pillar.radius + margin_m;
    if (d <= pillar.radius || s.farthest_m <= beyond) continue;
    const double half_cone = std::asin(0.5 * pillar.radius / d);
    // The cone from lo to hi, in two parts where it crosses the bearings' wrap.
    const double lo = geometry::WrapAngle(Bearing(centre) - half_cone);
    const double hi = lo + 2 * half_cone;
    size_t in_cone = 0;
    const auto all_beyond_in = [&](double from, double to) {
      return AllBeyond(s.scan->points, s.sweeps, from, to, beyond, in_cone);
    };
    const bool all_beyond = hi <= geometry::kPi
                                ? all_beyond_in(lo, hi)
                                : all_beyond_in(lo, geometry::kPi) &&
                                      all_beyond_in(-geometry::kPi, hi - 2 * geometry::kPi);
    if (all_beyond && in_cone > 0) ++through;
  }
  return through;
}

}  // namespace structloc::map_building
