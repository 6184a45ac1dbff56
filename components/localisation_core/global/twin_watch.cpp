// Page's test between a tracked pose and its twins (see header).
#include "structloc/localisation_core/global/twin_watch.hpp"

#include <algorithm>
#include <cmath>

namespace structloc::localisation_core {

TwinWatch::TwinWatch(const GlobalLocaliser& localiser, const geometry::Pose2D& sensor_mount,
                     std::vector<geometry::Pose2D> twins, const HypothesisOptions& test,
                     double allowance_points)
    : localiser_(localiser), mount_(sensor_mount), twins_(std::move(twins)), test_(test) {
  CheckHypothesisOptions(test_);
  // A point explained at one pose and not at the other moves the mean
  // log-likelihood by ln(1 / u) / fit_points; a step counts it
  // readings_per_step times.
  allowance_ = allowance_points * test_.readings_per_step *
               std::log(1.0 / test_.unexplained_likelihood) / test_.fit_points;
  Clear();
}

void TwinWatch::Clear() {
  last_weighed_.reset();
  evidence_.assign(twins_.size(), 0.0);
  since_.assign(twins_.size(), 0.0);
}

bool TwinWatch::Due(const geometry::Pose2D& tracked) const {
  if (twins_.empty()) return false;
  if (!last_weighed_) return true;
  return std::hypot(tracked.x - last_weighed_->x, tracked.y - last_weighed_->y) >=
             test_.evidence_step_m ||
         std::abs(geometry::WrapAngle(tracked.theta - last_weighed_->theta)) >=
             test_.evidence_step_rad;
}

std::optional<TwinDecision> TwinWatch::Observe(const std::vector<Eigen::Vector2d>& laser_points,
                                               double stamp, const geometry::Pose2D& tracked,
                                               double min_share) {
  if (!Due(tracked)) return std::nullopt;
  last_weighed_ = tracked;
  const auto points = localiser_.FitPoints(laser_points, test_.fit_points);
  auto fit = [&](const geometry::Pose2D& robot) {
    return localiser_.FitAt(points, geometry::Compose(robot, mount_), test_.unexplained_likelihood);
  };
  const auto at_tracked = fit(tracked);
  std::optional<TwinDecision> decision;
  for (size_t k = 0; k < twins_.size(); ++k) {
    const geometry::Pose2D twin = geometry::Compose(twins_[k], tracked);
    const auto at_twin = fit(twin);
    const double ratio =
        test_.readings_per_step * (at_twin.mean_log_likelihood - at_tracked.mean_log_likelihood);
    if (evidence_[k] == 0.0) since_[k] = stamp;
    evidence_[k] = std::max(0.0, evidence_[k] + ratio - allowance_);
    const bool decided = evidence_[k] >= test_.decision_log_ratio &&
                         at_twin.share > at_tracked.share &&
                         at_twin.share >= std::max(min_share, test_.min_share);
    if (decided && !decision) decision = TwinDecision{stamp, tracked, twin, since_[k]};
  }
  return decision;
}

}  // namespace structloc::localisation_core
