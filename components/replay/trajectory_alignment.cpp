// Rigid and similarity alignment of a trajectory onto ground truth (see header).
#include "structloc/replay/trajectory_alignment.hpp"

#include <Eigen/Core>
#include <cmath>

namespace structloc::replay {

namespace {

// The least-squares similarity (or, with `fit_scale` false, rigid motion)
// from the estimate's positions to the truth's at the same stamps.
std::optional<Similarity> Align(const std::vector<log_formats::StampedPose>& estimate,
                                const std::vector<log_formats::StampedPose>& truth,
                                double tolerance_s, bool fit_scale) {
  std::vector<Eigen::Vector2d> p, q;  // matched positions: estimate, truth
  for (const auto& e : estimate) {
    const auto* t = log_formats::Nearest(truth, e.stamp, tolerance_s);
    if (t == nullptr) continue;
    p.push_back(e.pose.Translation());
    q.push_back(t->pose.Translation());
  }
  if (p.size() < 2) return std::nullopt;
  Eigen::Vector2d mp = Eigen::Vector2d::Zero(), mq = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < p.size(); ++i) {
    mp += p[i];
    mq += q[i];
  }
  mp /= static_cast<double>(p.size());
  mq /= static_cast<double>(q.size());
  // The rotation maximising sum q_i . R p_i (centred): its angle is that of
  // (sum of dot products, sum of cross products); the scale is the length
  // of that vector over the estimate's spread.
  double dot = 0.0, cross = 0.0, spread = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d a = p[i] - mp, b = q[i] - mq;
    dot += a.dot(b);
    cross += a.x() * b.y() - a.y() * b.x();
    spread += a.squaredNorm();
  }
  if (dot == 0.0 && cross == 0.0) return std::nullopt;
  const double theta = std::atan2(cross, dot);
  const double scale = fit_scale ? std::hypot(dot, cross) / spread : 1.0;
  const double c = scale * std::cos(theta), s = scale * std::sin(theta);
  return Similarity{{mq.x() - (c * mp.x() - s * mp.y()), mq.y() - (s * mp.x() + c * mp.y()), theta},
                    scale};
}

}  // namespace

std::optional<geometry::Pose2D> AlignTrajectory(
    const std::vector<log_formats::StampedPose>& estimate,
    const std::vector<log_formats::StampedPose>& truth, double tolerance_s) {
  const auto rigid = Align(estimate, truth, tolerance_s, false);
  if (!rigid) return std::nullopt;
  return rigid->motion;
}

std::optional<Similarity> AlignTrajectoryWithScale(
    const std::vector<log_formats::StampedPose>& estimate,
    const std::vector<log_formats::StampedPose>& truth, double tolerance_s) {
  return Align(estimate, truth, tolerance_s, true);
}

std::optional<ScaledError> CompareAlignedWithScale(
    const std::vector<log_formats::StampedPose>& estimate,
    const std::vector<log_formats::StampedPose>& truth, double tolerance_s) {
  const auto similarity = AlignTrajectoryWithScale(estimate, truth, tolerance_s);
  if (!similarity) return std::nullopt;
  return ScaledError{similarity->scale,
                     CompareTrajectories(Moved(estimate, *similarity), truth, tolerance_s)};
}

std::optional<TrajectoryError> CompareAligned(const std::vector<log_formats::StampedPose>& estimate,
                                              const std::vector<log_formats::StampedPose>& truth,
                                              double tolerance_s) {
  const auto motion = AlignTrajectory(estimate, truth, tolerance_s);
  if (!motion) return std::nullopt;
  return CompareTrajectories(Moved(estimate, *motion), truth, tolerance_s);
}

std::vector<log_formats::StampedPose> Moved(const std::vector<log_formats::StampedPose>& trajectory,
                                            const geometry::Pose2D& motion) {
  return Moved(trajectory, Similarity{motion, 1.0});
}

std::vector<log_formats::StampedPose> Moved(const std::vector<log_formats::StampedPose>& trajectory,
                                            const Similarity& similarity) {
  std::vector<log_formats::StampedPose> out;
  out.reserve(trajectory.size());
  for (const auto& p : trajectory) {
    const geometry::Pose2D scaled{similarity.scale * p.pose.x, similarity.scale * p.pose.y,
                                  p.pose.theta};
    out.push_back({p.stamp, geometry::Compose(similarity.motion, scaled)});
  }
  return out;
}

}  // namespace structloc::replay
