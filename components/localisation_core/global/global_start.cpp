// Global start-up of a robot without a pose (see header).
#include "structloc/localisation_core/global/global_start.hpp"

#include <cmath>

namespace structloc::localisation_core {

GlobalStart::GlobalStart(const world_model::WorldModel& world, const geometry::Pose2D& sensor_mount,
                         const Eigen::Matrix3d& covariance, const GlobalLocaliserOptions& options,
                         const RecentScansOptions& recent, const HypothesisOptions& hypotheses)
    : search_(world, options),
      mount_(sensor_mount),
      covariance_(covariance),
      recent_(recent),
      hypotheses_(search_, sensor_mount, hypotheses) {}

std::vector<Eigen::Vector2d> LaserPoints(const SessionScan& scan) {
  const auto& g = scan.geometry;
  const double max_range = g.range_max > 0.0 ? g.range_max - 1e-3 : INFINITY;
  return ScanPointsInLaserFrame(scan.ranges, g.angle_min, g.angle_increment, g.range_min,
                                max_range);
}

GlobalStart::Attempt GlobalStart::Try(const SessionScan& scan) const {
  return Locate(scan, nullptr);
}

GlobalStart::Attempt GlobalStart::Try(const SessionScan& scan, const geometry::Pose2D& odometry) {
  return Try(LaserPoints(scan), scan.geometry.stamp, odometry);
}

GlobalStart::Attempt GlobalStart::Try(const std::vector<Eigen::Vector2d>& points, double stamp,
                                      const geometry::Pose2D& odometry) {
  const auto readings = recent_.WithScan(points, geometry::Compose(odometry, mount_));
  if (hypotheses_.Holding()) {
    const auto verdict = hypotheses_.Update(points, odometry);
    if (verdict == HypothesisTracker::Verdict::kHolding) {
      Attempt attempt;
      attempt.searched = false;
      attempt.hypotheses = hypotheses_.Hypotheses();
      attempt.seeded = hypotheses_.Seeded();
      return attempt;
    }
    travel_before_m_ += hypotheses_.TravelM();
    if (verdict == HypothesisTracker::Verdict::kCommitted)
      return Verify(stamp, readings, points, odometry, *hypotheses_.Committed());
  }
  return SearchAndSeed(stamp, readings, points, odometry);
}

GlobalStart::Attempt GlobalStart::SearchAndSeed(double stamp, const Readings& readings,
                                                const std::vector<Eigen::Vector2d>& points,
                                                const geometry::Pose2D& odometry) {
  return FollowUp(stamp, search_.Locate(readings), points, odometry);
}

// A search's answer: a pose found ends the start-up, an ambiguous one starts
// hypotheses, none leaves nothing to follow (the next hypotheses start a new
// count of travel).
GlobalStart::Attempt GlobalStart::FollowUp(double stamp, GlobalResult result,
                                           const std::vector<Eigen::Vector2d>& points,
                                           const geometry::Pose2D& odometry) {
  Attempt attempt = Decide(stamp, std::move(result));
  if (!attempt.found && attempt.result.decision == GlobalDecision::kAmbiguous &&
      geometry::IsFinite(odometry)) {
    attempt.seeded = hypotheses_.Seed(attempt.result, points, odometry);
    attempt.hypotheses = hypotheses_.Hypotheses();
    return attempt;
  }
  travel_before_m_ = 0.0;
  hypotheses_.Clear();
  return attempt;
}

// The hypothesis left standing is committed only if a search of the whole
// map with the scans of the last metres does not put the robot elsewhere
// with a better fit: the hypotheses came from one search, which can miss the
// true pose (more look-alike places than hypotheses, or a near-identical
// hit crowding it out), and then the least wrong one would be left standing.
GlobalStart::Attempt GlobalStart::Verify(double stamp, const Readings& readings,
                                         const std::vector<Eigen::Vector2d>& points,
                                         const geometry::Pose2D& odometry,
                                         const Hypothesis& standing) {
  const geometry::Pose2D laser = geometry::Compose(standing.pose, mount_);
  GlobalResult check = search_.Locate(readings);
  const double travel = travel_before_m_;
  const size_t seeded = hypotheses_.Seeded();
  const bool elsewhere = check.best && Distinct(check.best->pose, laser, search_.Options());
  if (!elsewhere || search_.Score(readings, laser) >= check.best->score) {
    Attempt attempt;
    attempt.result = std::move(check);
    attempt.found = InitialPoseInput{stamp, standing.pose, covariance_};
    attempt.hypotheses = {standing};
    travel_before_m_ = 0.0;
    hypotheses_.Clear();
    attempt.travel_m = travel;
    attempt.seeded = seeded;
    return attempt;
  }
  Attempt attempt = FollowUp(stamp, std::move(check), points, odometry);
  attempt.refused = standing;
  if (attempt.found) {
    attempt.travel_m = travel;
    attempt.seeded = seeded;
  } else if (attempt.hypotheses.empty()) {
    travel_before_m_ = travel;  // the travel goes on counting to the next hypotheses
    attempt.seeded = seeded;
  }
  return attempt;
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
  return RobotPoseAt(scan.geometry.stamp, *nearest);
}

GlobalStart::Attempt GlobalStart::Locate(const SessionScan& scan,
                                         const SearchWindow* window) const {
  return Decide(scan.geometry.stamp, search_.Locate(LaserPoints(scan), window));
}

GlobalStart::Attempt GlobalStart::Decide(double stamp, GlobalResult result) const {
  Attempt attempt;
  attempt.result = std::move(result);
  if (attempt.result.decision == GlobalDecision::kFound)
    attempt.found = RobotPoseAt(stamp, attempt.result.best->pose);
  return attempt;
}

InitialPoseInput GlobalStart::RobotPoseAt(double stamp, const geometry::Pose2D& laser) const {
  return {stamp, geometry::Compose(laser, geometry::Inverse(mount_)), covariance_};
}

}  // namespace structloc::localisation_core
