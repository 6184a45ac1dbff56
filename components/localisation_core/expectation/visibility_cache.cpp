// Visibility kept for the places the robot passes (see header).
#include "structloc/localisation_core/expectation/visibility_cache.hpp"

#include <cmath>
#include <stdexcept>

#include "structloc/localisation_core/expectation/scan_visibility.hpp"

namespace structloc::localisation_core {

VisibilityCache::VisibilityCache(const world_model::WorldModel& world,
                                 const world_model::Scene& scene, double reach_m, double reach_rad,
                                 size_t capacity)
    : world_(world), scene_(scene), reach_m_(reach_m), reach_rad_(reach_rad) {
  if (!(reach_m > 0.0) || !(reach_rad > 0.0) || capacity < 2) {
    throw std::invalid_argument(
        "VisibilityCache: the reach must be positive and the capacity at least 2");
  }
  entries_.resize(capacity);
  workspace_.Reserve(world, scene);
}

bool VisibilityCache::SetView(const world_model::VisibilityOptions& view) {
  if (view_ && SameView(*view_, view)) return false;
  view_ = view;
  for (auto& e : entries_) e.valid = false;
  newest_ = -1;
  return true;
}

bool VisibilityCache::FullCircle() const {
  return view_ && view_->view_max_rad - view_->view_min_rad >= 2.0 * geometry::kPi - 1e-9;
}

bool VisibilityCache::Holds(int entry, const geometry::Pose2D& sensor) const {
  const auto& e = entries_[static_cast<size_t>(entry)];
  return e.valid && (sensor.Translation() - e.pose.Translation()).norm() < reach_m_ &&
         (FullCircle() || std::abs(geometry::WrapAngle(sensor.theta - e.pose.theta)) < reach_rad_);
}

int VisibilityCache::Find(const geometry::Pose2D& sensor) {
  int best = -1;
  double best_m = INFINITY;
  for (size_t i = 0; i < entries_.size(); ++i) {
    if (!Holds(static_cast<int>(i), sensor)) continue;
    const double m = (sensor.Translation() - entries_[i].pose.Translation()).norm();
    if (m < best_m) {
      best = static_cast<int>(i);
      best_m = m;
    }
  }
  if (best >= 0) entries_[static_cast<size_t>(best)].used = ++tick_;
  return best;
}

int VisibilityCache::Compute(const geometry::Pose2D& sensor, int keep) {
  if (!view_) throw std::logic_error("VisibilityCache::Compute before SetView");
  size_t slot = entries_.size();
  for (size_t i = 0; i < entries_.size(); ++i) {
    if (static_cast<int>(i) == keep) continue;
    if (slot == entries_.size() || !entries_[i].valid ||
        (entries_[slot].valid && entries_[i].used < entries_[slot].used)) {
      slot = i;
    }
    if (!entries_[slot].valid) break;
  }
  auto& e = entries_[slot];
  world_model::ComputeVisibility(world_, scene_, sensor, *view_, workspace_);
  // Only what is seen is kept (the work space is sized for the whole map).
  e.visibility.walls.assign(workspace_.walls.begin(), workspace_.walls.end());
  e.visibility.corners.assign(workspace_.corners.begin(), workspace_.corners.end());
  e.visibility.cylinders.assign(workspace_.cylinders.begin(), workspace_.cylinders.end());
  e.pose = sensor;
  e.valid = true;
  e.used = ++tick_;
  ++computations_;
  newest_ = static_cast<int>(slot);
  return newest_;
}

}  // namespace structloc::localisation_core
