// Where a robot without a pose is (no initial pose given, no saved state, or
// a request to relocalise): each incoming scan goes to the global localiser
// until one gives a "found" pose, never an unfound one; that pose (the
// laser's, turned into the robot's with the sensor mount) becomes the
// initial pose at the scan's stamp. With the robot's odometry, each scan is
// searched together with those taken on the last metres (RecentScans), and
// an "ambiguous" answer (a symmetric building) starts several hypotheses
// that the following scans weigh (HypothesisTracker); no search runs while
// they are held. The one left standing is committed once a search with the
// last metres' scans does not put the robot elsewhere with a better fit;
// otherwise hypotheses start afresh from that search. The
// localisation component and replay both start a robot through this class.
// TryNear searches only around a pose the robot is believed to be near (a
// pose hint: PoseHintCheck). The localisation component runs it; DDS-free.
#pragma once

#include <optional>

#include "structloc/localisation_core/global/global_localiser.hpp"
#include "structloc/localisation_core/global/hypothesis_tracker.hpp"
#include "structloc/localisation_core/global/recent_scans.hpp"
#include "structloc/localisation_core/scan/session_scan.hpp"
#include "structloc/localisation_core/tracking/session_inbox.hpp"

namespace structloc::localisation_core {

// A scan's points in the laser frame as the searches take them (within its
// range limits; a reading at range_max is no return).
std::vector<Eigen::Vector2d> LaserPoints(const SessionScan& scan);

class GlobalStart {
 public:
  // `covariance`: of a pose found (the tracker's initial covariance).
  GlobalStart(const world_model::WorldModel& world, const geometry::Pose2D& sensor_mount,
              const Eigen::Matrix3d& covariance, const GlobalLocaliserOptions& options = {},
              const RecentScansOptions& recent = {}, const HypothesisOptions& hypotheses = {});

  struct Attempt {
    bool searched = true;  // a global search ran (else the hypotheses held were weighed)
    GlobalResult result;   // laser poses (when searched)
    std::optional<InitialPoseInput> found;  // the robot's initial pose, when found
    std::vector<Hypothesis> hypotheses;     // held after this scan (robot poses), best first
    // When found through hypotheses: the odometric travel from the search
    // that first started them, and how many the last such search started.
    std::optional<double> travel_m;
    size_t seeded = 0;
    // The hypothesis left standing that a search with the last metres'
    // scans refused (it put the robot elsewhere, with a better fit); the
    // hypotheses are then started afresh from that search.
    std::optional<Hypothesis> refused;
  };
  Attempt Try(const SessionScan& scan) const;
  // The same together with the scans given here before, placed by the
  // robot's odometric pose at each (`odometry`, at this scan's stamp); the
  // scan alone when that pose is not finite.
  Attempt Try(const SessionScan& scan, const geometry::Pose2D& odometry);
  // The same for a scan's points (laser frame) taken at `stamp`.
  Attempt Try(const std::vector<Eigen::Vector2d>& laser_points, double stamp,
              const geometry::Pose2D& odometry);
  // Forgets those scans and the hypotheses held: the robot was carried
  // away, or has a pose.
  void ForgetRecentScans() {
    recent_.Clear();
    hypotheses_.Clear();
    travel_before_m_ = 0.0;
  }
  bool HoldingHypotheses() const { return hypotheses_.Holding(); }
  const GlobalLocaliser& Localiser() const { return search_; }
  // The same, over robot positions within `radius_m` of `robot_pose` and
  // headings within `heading_rad` of its heading.
  Attempt TryNear(const SessionScan& scan, const geometry::Pose2D& robot_pose, double radius_m,
                  double heading_rad) const;
  // Of an ambiguous result's best pose and runner-up, the one within
  // `distance_m` and `heading_rad` of `robot_pose` (the nearer if both are),
  // as the robot's initial pose at the scan's stamp; nullopt if neither is.
  std::optional<InitialPoseInput> NearestOfTie(const SessionScan& scan, const GlobalResult& result,
                                               const geometry::Pose2D& robot_pose,
                                               double distance_m, double heading_rad) const;

 private:
  Attempt Locate(const SessionScan& scan, const SearchWindow* window) const;
  Attempt Decide(double stamp, GlobalResult result) const;

  Attempt SearchAndSeed(double stamp, const Readings& readings,
                        const std::vector<Eigen::Vector2d>& points,
                        const geometry::Pose2D& odometry);
  Attempt FollowUp(double stamp, GlobalResult result, const std::vector<Eigen::Vector2d>& points,
                   const geometry::Pose2D& odometry);
  Attempt Verify(double stamp, const Readings& readings, const std::vector<Eigen::Vector2d>& points,
                 const geometry::Pose2D& odometry, const Hypothesis& standing);
  InitialPoseInput RobotPoseAt(double stamp, const geometry::Pose2D& laser) const;

  GlobalLocaliser search_;
  geometry::Pose2D mount_;
  Eigen::Matrix3d covariance_;
  RecentScans recent_;
  HypothesisTracker hypotheses_;
  double travel_before_m_ = 0.0;  // by hypotheses given up since the first was started
};

}  // namespace structloc::localisation_core
