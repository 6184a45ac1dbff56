// Odometry history ring buffer (see header).
#include "structloc/localisation_core/tracking/odometry_history.hpp"

#include <stdexcept>

namespace structloc::localisation_core {

OdometryHistory::OdometryHistory(size_t capacity) : samples_(capacity) {
  if (capacity < 2) throw std::invalid_argument("odometry history: capacity must be >= 2");
}

OdometryHistory::AddResult OdometryHistory::Add(double stamp, const geometry::Pose2D& pose) {
  if (!std::isfinite(stamp) || !geometry::IsFinite(pose)) return AddResult::kNonFinite;
  if (size_ > 0 && !(stamp > Newest())) return AddResult::kOutOfOrder;
  if (size_ == samples_.size()) {
    head_ = (head_ + 1) % samples_.size();
    --size_;
  }
  samples_[(head_ + size_) % samples_.size()] = {stamp, pose};
  ++size_;
  return AddResult::kAdded;
}

double OdometryHistory::Oldest() const {
  return size_ ? Get(0).stamp : NAN;
}
double OdometryHistory::Newest() const {
  return size_ ? Get(size_ - 1).stamp : NAN;
}

std::optional<geometry::Pose2D> OdometryHistory::At(double stamp) const {
  if (size_ == 0 || !(stamp >= Oldest()) || !(stamp <= Newest())) return std::nullopt;
  size_t lo = 0, hi = size_ - 1;  // invariant: Get(lo).stamp <= stamp <= Get(hi).stamp
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    if (Get(mid).stamp <= stamp) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const auto& a = Get(lo);
  const auto& b = Get(hi);
  if (hi == lo || b.stamp == a.stamp) return a.pose;
  return geometry::Interpolate(a.pose, b.pose, (stamp - a.stamp) / (b.stamp - a.stamp));
}

std::optional<geometry::Pose2D> OdometryHistory::AtOrExtrapolated(
    double stamp, double max_extrapolation_s) const {
  if (size_ < 2 || !(stamp > Newest())) return At(stamp);
  if (stamp - Newest() > max_extrapolation_s) return std::nullopt;
  const auto& a = Get(size_ - 2);
  const auto& b = Get(size_ - 1);
  const double f = (stamp - a.stamp) / (b.stamp - a.stamp);  // > 1: beyond b
  return geometry::Pose2D{
      a.pose.x + f * (b.pose.x - a.pose.x), a.pose.y + f * (b.pose.y - a.pose.y),
      geometry::WrapAngle(a.pose.theta + f * geometry::WrapAngle(b.pose.theta - a.pose.theta))};
}

}  // namespace structloc::localisation_core
