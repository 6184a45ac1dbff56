// Global start-up of a robot without a pose (see header).
#include "structloc/localisation_core/global_start.hpp"

#include <cmath>

namespace structloc::localisation_core {

GlobalStart::GlobalStart(const world_model::WorldModel& world, const geometry::Pose2D& sensor_mount,
                         const Eigen::Matrix3d& covariance, const GlobalLocaliserOptions& options,
                         const RecentScansOptions& recent)
    : search_(world, options), mount_(sensor_mount), covariance_(covariance), recent_(recent) {}

namespace {

std::vector<Eigen::Vector2d> LaserPoints(const SessionScan& scan) {
  const auto& g = scan.geometry;
  const double max_range = g.range_max > 0.0 ? g.range_max - 1e-3 : INFINITY;
  return ScanPointsInLaserFrame(scan.ranges, g.angle_min, g.angle_increment, g.range_min,
                                max_range);
}

}  // namespace

GlobalStart::Attempt GlobalStart::Try(const SessionScan& scan) const {
  return Locate(scan, nullptr);
}

GlobalStart::Attempt GlobalStart::Try(const SessionScan& scan, const geometry::Pose2D& odometry) {
  return Decide(scan, search_.Locate(recent_.WithScan(LaserPoints(scan),
                                                      geometry::Compose(odometry, mount_))));
}

GlobalStart::Attempt GlobalStart::TryNear(const SessionScan& scan,
                                          const geometry::Pose2D& robot_pose, double radius_m,
                                          double heading_rad) const {
  const SearchWindow window{geometry::Compose(robot_pose, mount_), radius_m, heading_rad};
  return Locate(scan, &window);
}

std::optional<InitialPoseInput> GlobalStart::NearestOfTie(const SessionScan& scan,
                                                          const GlobalResult& result,
                                                          const geometry::Pose2D& robot_pose,
                                                          double distance_m,
                                                          double heading_rad) const {
  const geometry::Pose2D laser = geometry::Compose(robot_pose, mount_);
  std::optional<geometry::Pose2D> nearest;
  double nearest_m = INFINITY;
  for (const auto* candidate : {&result.best, &result.runner_up}) {
    if (!candidate->has_value()) continue;
    const geometry::Pose2D& p = (*candidate)->pose;
    const double d = std::hypot(p.x - laser.x, p.y - laser.y);
    if (d <= distance_m && std::abs(geometry::WrapAngle(p.theta - laser.theta)) <= heading_rad &&
        d < nearest_m) {
      nearest = p;
      nearest_m = d;
    }
  }
  if (!nearest) return std::nullopt;
  return InitialPoseInput{scan.geometry.stamp,
                          geometry::Compose(*nearest, geometry::Inverse(mount_)), covariance_};
}

GlobalStart::Attempt GlobalStart::Locate(const SessionScan& scan,
                                         const SearchWindow* window) const {
  return Decide(scan, search_.Locate(LaserPoints(scan), window));
}

GlobalStart::Attempt GlobalStart::Decide(const SessionScan& scan, GlobalResult result) const {
  Attempt attempt;
  attempt.result = std::move(result);
  if (attempt.result.decision == GlobalDecision::kFound) {
    attempt.found = InitialPoseInput{
        scan.geometry.stamp,
        geometry::Compose(attempt.result.best->pose, geometry::Inverse(mount_)), covariance_};
  }
  return attempt;
}

}  // namespace structloc::localisation_core
