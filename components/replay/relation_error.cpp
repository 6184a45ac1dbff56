// The relation metric (see header).
#include "structloc/replay/relation_error.hpp"

#include <cmath>

namespace structloc::replay {
namespace {

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
    const auto* a = log_formats::Nearest(trajectory, r.t1, tolerance_s);
    const auto* b = log_formats::Nearest(trajectory, r.t2, tolerance_s);
    if (a == nullptr || b == nullptr) {
      ++out.missing;
      continue;
    }
    const geometry::Pose2D estimated = geometry::Between(a->pose, b->pose);
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
