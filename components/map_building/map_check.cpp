// Agreement of a map with a corrected recording (see header).
#include "structloc/map_building/map_check.hpp"

#include <algorithm>
#include <cmath>

#include "structloc/map_building/nearest_wall.hpp"
#include "structloc/map_building/quantile.hpp"

namespace structloc::map_building {
namespace {

struct Hits {
  std::vector<double> distances;  // signed, > 0 on the laser's side
  std::vector<uint32_t> scans;
};

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto mid = values.begin() + static_cast<long>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

SurfaceAgreement Summarise(Hits& hits, const MapCheckOptions& options) {
  SurfaceAgreement a;
  a.readings = hits.distances.size();
  if (a.readings == 0) return a;
  std::vector<double> magnitudes;
  double sum = 0.0, sum2 = 0.0;
  for (const double d : hits.distances) {
    magnitudes.push_back(std::abs(d));
    sum += d;
    sum2 += d * d;
  }
  a.median_m = Median(magnitudes);
  a.rms_m = std::sqrt(sum2 / static_cast<double>(a.readings));
  a.mean_offset_m = sum / static_cast<double>(a.readings);
  std::sort(hits.scans.begin(), hits.scans.end());
  a.scans =
      static_cast<size_t>(std::unique(hits.scans.begin(), hits.scans.end()) - hits.scans.begin());
  a.disagrees = a.median_m > options.max_median_m;
  return a;
}

// Distance of p from a wall, signed > 0 on the side of `laser`.
double SignedWallDistance(const world_model::Wall& wall, const Eigen::Vector2d& p,
                          const Eigen::Vector2d& laser, double distance) {
  const Eigen::Vector2d normal(std::cos(wall.line.alpha), std::sin(wall.line.alpha));
  const double side_p = normal.dot(p) - wall.line.r;
  const double side_laser = normal.dot(laser) - wall.line.r;
  return (side_p * side_laser >= 0.0) ? distance : -distance;
}

}  // namespace

MapCheckReport CheckMap(const world_model::WorldModel& world, const std::vector<PosedScan>& scans,
                        const MapCheckOptions& options, std::vector<Eigen::Vector2d>* unexplained) {
  const NearestWallIndex index(world, options.near_m);
  std::vector<Hits> wall_hits(world.Walls().size()), pillar_hits(world.Cylinders().size());
  std::vector<double> all;
  MapCheckReport report;
  report.scans = scans.size();
  for (const auto& scan : scans) {
    const Eigen::Vector2d laser = scan.laser_pose.Translation();
    const auto id = static_cast<uint32_t>(scan.index);
    for (const auto& local : scan.points) {
      const Eigen::Vector2d p = scan.laser_pose.Apply(local);
      ++report.readings;
      const auto nearest = index.Nearest(p);
      if (nearest.kind == NearestSurface::Kind::kNone) {
        if (unexplained != nullptr) unexplained->push_back(p);
        continue;
      }
      ++report.explained;
      all.push_back(nearest.distance_m);
      if (nearest.kind == NearestSurface::Kind::kWall) {
        const auto& wall = world.Walls()[nearest.index];
        auto& hits = wall_hits[nearest.index];
        hits.distances.push_back(SignedWallDistance(wall, p, laser, nearest.distance_m));
        hits.scans.push_back(id);
      } else {
        const auto& pillar = world.Cylinders()[nearest.index];
        auto& hits = pillar_hits[nearest.index];
        hits.distances.push_back((p - pillar.centre).norm() - pillar.radius);
        hits.scans.push_back(id);
      }
    }
  }
  report.median_m = Median(all);
  report.p90_m = Quantile(all, 0.9);
  double sum2 = 0.0;
  for (const double d : all) sum2 += d * d;
  report.rms_m = all.empty() ? 0.0 : std::sqrt(sum2 / static_cast<double>(all.size()));
  for (auto& hits : wall_hits) {
    report.walls.push_back(Summarise(hits, options));
    const auto& a = report.walls.back();
    if (a.readings == 0) {
      ++report.walls_never_seen;
    } else if (a.readings < options.min_readings) {
      ++report.walls_rarely_seen;
    }
    if (a.disagrees) ++report.walls_disagreeing;
  }
  for (auto& hits : pillar_hits) report.pillars.push_back(Summarise(hits, options));
  return report;
}

}  // namespace structloc::map_building
