// Pillars from arcs seen repeatedly (see header).
#include "structloc/map_building/pillar_finding.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "structloc/fitting/circle_fit.hpp"
#include "structloc/fitting/line_fit.hpp"
#include "structloc/map_building/seen_through.hpp"

namespace structloc::map_building {
namespace {

// Checks one run of points (laser frame) for a pillar-like arc.
bool ArcCircle(const std::vector<Eigen::Vector2d>& run, const PillarOptions& options,
               Eigen::Vector2d& centre, double& radius) {
  std::vector<double> xs, ys;
  fitting::LineSums sums;
  for (const auto& p : run) {
    xs.push_back(p.x());
    ys.push_back(p.y());
    sums.Add(p.x() - run.front().x(), p.y() - run.front().y());
  }
  const auto line = fitting::FitLine(sums, run.front().x(), run.front().y());
  if (!line.degenerate &&
      std::sqrt(line.sse / static_cast<double>(run.size())) < options.min_line_rms_m)
    return false;
  const auto circle = fitting::FitCircle(xs, ys, 0, run.size());
  if (!circle.ok || circle.radius < options.min_radius_m || circle.radius > options.max_radius_m)
    return false;
  centre = {circle.xc, circle.yc};
  radius = circle.radius;
  double sse = 0.0;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : run) {
    const double e = (p - centre).norm() - radius;
    sse += e * e;
    mean += p;
  }
  mean /= static_cast<double>(run.size());
  if (std::sqrt(sse / static_cast<double>(run.size())) > options.max_rms_m) return false;
  const Eigen::Vector2d u = run.front() - centre, v = run.back() - centre;
  if (std::abs(std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v))) < options.min_arc_rad)
    return false;
  // A pillar bulges towards the laser (at the origin): its centre lies beyond the arc.
  return centre.norm() > mean.norm();
}

// Two standing pillars cannot overlap: discs that do are one pillar built
// twice (where passes of the path disagree by centimetres, its sightings
// fall into two groups), merged weighted by their scans. Returns how many
// were merged away.
size_t MergeOverlapping(std::vector<world_model::Cylinder>& pillars, std::vector<double>& weights) {
  size_t merged = 0;
  for (size_t i = 0; i < pillars.size(); ++i) {
    for (size_t j = i + 1; j < pillars.size();) {
      auto& a = pillars[i];
      const auto& b = pillars[j];
      if ((b.centre - a.centre).norm() >= a.radius + b.radius) {
        ++j;
        continue;
      }
      const double w = weights[i] + weights[j];
      a.centre = (weights[i] * a.centre + weights[j] * b.centre) / w;
      a.radius = (weights[i] * a.radius + weights[j] * b.radius) / w;
      weights[i] = w;
      pillars.erase(pillars.begin() + static_cast<long>(j));
      weights.erase(weights.begin() + static_cast<long>(j));
      ++merged;
      j = i + 1;  // the grown disc may overlap one passed over
    }
  }
  return merged;
}

}  // namespace

void PillarAccumulator::Add(uint32_t scan, const geometry::Pose2D& laser_pose,
                            const std::vector<Eigen::Vector2d>& points) {
  if (!options_.enabled) return;
  size_t start = 0;
  for (size_t k = 1; k <= points.size(); ++k) {
    if (k < points.size() && (points[k] - points[k - 1]).norm() <= options_.max_point_gap_m)
      continue;
    if (static_cast<int>(k - start) >= options_.min_points) {
      const std::vector<Eigen::Vector2d> run(points.begin() + static_cast<long>(start),
                                             points.begin() + static_cast<long>(k));
      Eigen::Vector2d centre;
      double radius = 0.0;
      if (ArcCircle(run, options_, centre, radius))
        sightings_.push_back({laser_pose.Apply(centre), radius, scan});
    }
    start = k;
  }
}

std::vector<world_model::Cylinder> PillarAccumulator::Pillars(const std::vector<PosedScan>& posed,
                                                              PillarReport& report) const {
  report = {};
  report.sightings = sightings_.size();
  std::vector<bool> used(sightings_.size(), false);
  std::vector<world_model::Cylinder> pillars;
  std::vector<double> scan_counts;             // of each pillar's sightings
  std::optional<SeeThroughCheck> see_through;  // built when a pillar is first checked
  const auto seen_through_more_often = [&](const world_model::Cylinder& c, size_t sighted) {
    if (!see_through) see_through.emplace(posed);
    return see_through->ScansSeeingThrough(c, options_.see_through_margin_m) > sighted;
  };
  for (size_t i = 0; i < sightings_.size(); ++i) {
    if (used[i]) continue;
    std::vector<size_t> group{i};
    used[i] = true;
    Eigen::Vector2d centre = sightings_[i].centre;
    for (size_t j = i + 1; j < sightings_.size(); ++j) {
      if (used[j] || (sightings_[j].centre - centre).norm() > options_.merge_distance_m) continue;
      used[j] = true;
      group.push_back(j);
      centre += (sightings_[j].centre - centre) / static_cast<double>(group.size());
    }
    std::vector<uint32_t> scans;
    std::vector<double> radii;
    for (const size_t k : group) {
      scans.push_back(sightings_[k].scan);
      radii.push_back(sightings_[k].radius);
    }
    std::sort(scans.begin(), scans.end());
    const auto distinct = std::unique(scans.begin(), scans.end()) - scans.begin();
    if (distinct < options_.min_scans) {
      ++report.too_few_scans;
      continue;
    }
    std::nth_element(radii.begin(), radii.begin() + static_cast<long>(radii.size() / 2),
                     radii.end());
    world_model::Cylinder c;
    c.centre = centre;
    c.radius = radii[radii.size() / 2];
    if (options_.drop_seen_through && seen_through_more_often(c, static_cast<size_t>(distinct))) {
      ++report.seen_through;
      continue;
    }
    pillars.push_back(c);
    scan_counts.push_back(static_cast<double>(distinct));
  }
  report.merged = MergeOverlapping(pillars, scan_counts);
  report.pillars = pillars.size();
  return pillars;
}

}  // namespace structloc::map_building
