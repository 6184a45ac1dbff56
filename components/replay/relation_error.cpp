// The relation metric (see header).
#include "structloc/replay/relation_error.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace structloc::replay {
namespace {

std::optional<geometry::Pose2D> PoseAt(const std::vector<log_formats::StampedPose>& trajectory,
                                       double t, double tolerance_s) {
  auto it =
      std::lower_bound(trajectory.begin(), trajectory.end(), t,
                       [](const log_formats::StampedPose& p, double s) { return p.stamp < s; });
  const log_formats::StampedPose* best = nullptr;
  if (it != trajectory.end()) best = &*it;
  if (it != trajectory.begin() && (!best || t - (it - 1)->stamp < best->stamp - t))
    best = &*(it - 1);
  if (!best || std::abs(best->stamp - t) > tolerance_s) return std::nullopt;
  return best->pose;
}

void MeanAndStd(const std::vector<double>& v, double& mean, double& std) {
  mean = 0.0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double var = 0.0;
  for (double x : v) var += (x - mean) * (x - mean);
  std = std::sqrt(var / static_cast<double>(v.size()));
}

}  // namespace

RelationError CompareRelations(const std::vector<log_formats::StampedPose>& trajectory,
                               const std::vector<log_formats::Relation>& relations,
                               double tolerance_s) {
  RelationError out;
  std::vector<double> translation, rotation;
  for (const auto& r : relations) {
    const auto a = PoseAt(trajectory, r.t1, tolerance_s);
    const auto b = PoseAt(trajectory, r.t2, tolerance_s);
    if (!a || !b) {
      ++out.missing;
      continue;
    }
    const geometry::Pose2D estimated = geometry::Between(*a, *b);
    translation.push_back(std::hypot(estimated.x - r.relative.x, estimated.y - r.relative.y));
    rotation.push_back(std::abs(geometry::WrapAngle(estimated.theta - r.relative.theta)));
  }
  out.used = translation.size();
  if (out.used == 0) return out;
  MeanAndStd(translation, out.translation_mean_m, out.translation_std_m);
  MeanAndStd(rotation, out.rotation_mean_rad, out.rotation_std_rad);
  return out;
}

}  // namespace structloc::replay
