// What the reference-free path checks (structloc_path_scan_fit and
// structloc_revisit_fit) share: one scan's points indexed so that another
// scan's points, put in its frame by a path's relative pose, can be measured
// against its surfaces, and a path's laser poses at the log's scans. A pair
// of scans that a path places as the laser saw them fits closely; a path
// wrong between them shows as points off the surfaces (issue 41: whether the
// corrected poses or a SLAM path agrees better with the scans).
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/log_formats/tum_reader.hpp"
#include "structloc/map_building/posed_scans.hpp"
#include "structloc/world_model/point_grid.hpp"

namespace structloc::evaluation {

constexpr double kCapM = 0.1;         // a point farther than this from the other scan counts this
constexpr double kNeighbourM = 0.15;  // a neighbour farther than this is another surface

// The earlier scan of a pair, its points indexed for the nearest one.
class EarlierScan {
 public:
  using Points = std::vector<Eigen::Vector2d>;

  explicit EarlierScan(const Points& points) : points_(points), grid_(kCapM) {
    for (size_t i = 0; i < points.size(); ++i) grid_.Insert(points[i], i);
  }
  // Distance from q to the line through its nearest point and that point's
  // neighbour in beam order (to the point itself without one), at most kCapM.
  double Distance(const Eigen::Vector2d& q) const {
    double best = kCapM;
    int nearest = -1;
    grid_.ForEachNear(q, [&](size_t i) {
      const double d = (points_[i] - q).norm();
      if (d < best) best = d, nearest = static_cast<int>(i);
    });
    if (nearest < 0) return kCapM;
    for (const int j : {nearest + 1, nearest - 1}) {
      if (j < 0 || j >= static_cast<int>(points_.size())) continue;
      const Eigen::Vector2d along = points_[j] - points_[nearest];
      if (along.norm() > kNeighbourM || along.norm() == 0.0) continue;
      const Eigen::Vector2d normal(-along.y(), along.x());
      return std::abs(normal.normalized().dot(q - points_[nearest]));
    }
    return best;
  }
  // The mean Distance of `later`'s points put in this scan's frame by `step`.
  double MeanDistance(const Points& later, const geometry::Pose2D& step) const {
    double sum = 0.0;
    for (const auto& q : later) sum += Distance(step.Apply(q));
    return later.empty() ? kCapM : sum / static_cast<double>(later.size());
  }

 private:
  const Points& points_;
  world_model::PointGrid grid_;  // cells of kCapM: every point within it is found
};

// The laser's pose on `path` at each of the log's scans (none where the path
// has no pose within 1 ms of the scan's stamp); the log's laser lines give
// the laser's mounting on the robot.
inline std::vector<std::optional<geometry::Pose2D>> LaserPosesOnPath(
    const map_building::PosedScanLog& log, const std::vector<log_formats::StampedPose>& path) {
  geometry::Pose2D mount;
  for (const auto& s : log.scans) {
    if (s.robot_pose) {
      mount = geometry::Between(*s.robot_pose, s.laser_pose);
      break;
    }
  }
  std::vector<std::optional<geometry::Pose2D>> laser(log.scans.size());
  for (size_t i = 0; i < log.scans.size(); ++i) {
    if (const auto* p = log_formats::Nearest(path, log.scans[i].stamp, 1e-3)) {
      laser[i] = geometry::Compose(p->pose, mount);
    }
  }
  return laser;
}

}  // namespace structloc::evaluation
