// The last scans of a robot without a pose (see header).
#include "structloc/localisation_core/global/recent_scans.hpp"

#include <cmath>
#include <stdexcept>

namespace structloc::localisation_core {
namespace {

bool Finite(const geometry::Pose2D& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

double Distance(const geometry::Pose2D& a, const geometry::Pose2D& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

}  // namespace

RecentScans::RecentScans(const RecentScansOptions& options) : options_(options) {
  if (options.max_scans < 1)
    throw std::invalid_argument("recent scans option max_scans must be at least 1");
  if (!(options.max_travel_m >= 0.0) || !std::isfinite(options.max_travel_m))
    throw std::invalid_argument("recent scans option max_travel_m must be a finite number >= 0");
  if (!(options.min_spacing_m > 0.0) || !std::isfinite(options.min_spacing_m))
    throw std::invalid_argument("recent scans option min_spacing_m must be a positive number");
  if (!(options.min_turn_rad > 0.0 && options.min_turn_rad <= geometry::kPi))
    throw std::invalid_argument("recent scans option min_turn_rad must lie in (0, pi]");
}

bool RecentScans::FarApart(const geometry::Pose2D& a, const geometry::Pose2D& b) const {
  return Distance(a, b) >= options_.min_spacing_m ||
         std::abs(geometry::WrapAngle(a.theta - b.theta)) >= options_.min_turn_rad;
}

bool RecentScans::Add(const std::vector<Eigen::Vector2d>& points,
                      const geometry::Pose2D& laser_odometry) {
  if (!Finite(laser_odometry)) {
    Clear();
    return false;
  }
  Scan scan{{}, laser_odometry};
  scan.points.reserve(points.size());
  for (const auto& p : points)
    if (p.allFinite()) scan.points.push_back(p);
  // The newest becomes a kept scan once the next one is far enough from it
  // (or it is the first).
  if (has_newest_ && (kept_.empty() || FarApart(kept_.back().pose, newest_.pose)))
    kept_.push_back(std::move(newest_));
  newest_ = std::move(scan);
  has_newest_ = true;
  // Older scans beyond the path length or the count are of no more use.
  double travel = 0.0;
  const geometry::Pose2D* later = &newest_.pose;
  for (size_t i = kept_.size(); i-- > 0;) {
    travel += Distance(kept_[i].pose, *later);
    later = &kept_[i].pose;
    if (travel > options_.max_travel_m ||
        kept_.size() - i > static_cast<size_t>(options_.max_scans)) {
      kept_.erase(kept_.begin(), kept_.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      break;
    }
  }
  return true;
}

// Walking back from the newest: a kept scan too close to the one taken after
// it adds little and is left out.
std::vector<const RecentScans::Scan*> RecentScans::Combined() const {
  std::vector<const Scan*> scans;
  if (!has_newest_) return scans;
  scans.push_back(&newest_);
  for (size_t i = kept_.size(); i-- > 0 && scans.size() < static_cast<size_t>(options_.max_scans);)
    if (FarApart(kept_[i].pose, scans.back()->pose)) scans.push_back(&kept_[i]);
  return scans;
}

Readings RecentScans::InNewestFrame() const {
  Readings readings;
  if (has_newest_) readings.newest_points = newest_.points.size();
  const auto combined = Combined();
  readings.scans = combined.size();
  for (const Scan* scan : combined) {
    const geometry::Pose2D relative = geometry::Between(newest_.pose, scan->pose);
    for (const auto& p : scan->points) {
      readings.points.push_back(relative.Apply(p));
      readings.seen_from.push_back(relative.Translation());
    }
  }
  return readings;
}

Readings RecentScans::WithScan(const std::vector<Eigen::Vector2d>& points,
                               const geometry::Pose2D& laser_odometry) {
  return Add(points, laser_odometry) ? InNewestFrame() : OneScan(points);
}

size_t RecentScans::Scans() const {
  return Combined().size();
}

void RecentScans::Clear() {
  kept_.clear();
  has_newest_ = false;
}

}  // namespace structloc::localisation_core
