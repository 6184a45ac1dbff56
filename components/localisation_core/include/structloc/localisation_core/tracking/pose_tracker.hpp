// Tracks the robot pose over time around the Localiser, the way a ROS node's
// logic would, but without middleware: it keeps an odometry history, checks
// every input (counted reasons for what it refuses), de-skews scans from the
// history, runs the position update with a prior carried forward by odometry
// (covariance growing with the distance driven), and keeps the map -> odom
// correction so that between scans the pose follows odometry. A lost update
// never moves the correction: the robot keeps dead reckoning and says so.
// Run by the TrackingSession (tracking_session.hpp), which the localisation
// component and the offline replay share; its options come from the
// <tracking> block of the parameter file.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "structloc/localisation_core/global/global_localiser.hpp"
#include "structloc/localisation_core/localiser/localiser.hpp"
#include "structloc/localisation_core/tracking/odometry_filter.hpp"
#include "structloc/localisation_core/tracking/odometry_history.hpp"

namespace structloc::localisation_core {

struct TrackerOptions {
  double odometry_wait_s = 0.1;  // how long a scan may wait for odometry to cover it
  // Beams this far past the newest odometry are de-skewed by extrapolating it
  // instead of waiting for the next sample (latency).
  double max_extrapolation_s = 0.03;
  double max_future_s = 1.0;                // scans stamped further ahead of odometry are refused
  double max_odometry_speed_m_s = 5;        // faster odometry steps are jumps and refused
  double max_odometry_turn_rate_rad_s = 6;  // faster heading changes are jumps and refused
  // A scan whose beams span longer than this (time_increment x beams) is refused:
  // no scanner sweeps that slowly, and waiting for its odometry would stall the rest.
  double max_scan_duration_s = 1.0;
  double odometry_sigma_xy_per_m = 0.02;     // prior growth per metre driven (1 sigma)
  double odometry_sigma_theta_per_m = 0.01;  // rad per metre driven
  double odometry_sigma_theta_per_rad = 0.02;
  double initial_sigma_xy_m = 0.05;  // uncertainty of a given initial pose
  double initial_sigma_theta_rad = 0.03;
  bool deskew = true;  // de-skew scans from the odometry history
  // Odometry calibration in the filter (odometry_filter.hpp): initial sigma of
  // the distance and turn scale factors and of the heading drift, and how fast
  // they may change. 0 leaves the odometry uncorrected.
  double odometry_scale_sigma = 0.0;
  double odometry_drift_sigma_rad_per_m = 0.0;
  double calibration_walk_per_m = 0.0;
  // Directions the scan's features pin worse than this stay with odometry.
  double weak_std_m = 0.05;
  double weak_std_rad = 0.05;
  // No update unless the robot moved this far or turned this much since the
  // last one (a standing robot would pile up the same scan's errors); 0: always.
  double min_update_travel_m = 0.0;
  double min_update_turn_rad = 0.0;
  // Without a usable scan, the tracker is lost once its position sigma exceeds this.
  double lost_sigma_m = 0.2;
  // The whole-scan check (0 disables it and re-acquisition): the share of the
  // scan's points the map explains at the tracked pose. A correction that
  // lowers it by more than min_share_drop is refused; below min_explained_share
  // for reacquire_after_s the tracker searches around its pose, as far as the
  // odometric uncertainty says (at most reacquire_max_radius_m), and jumps
  // where the scan is explained clearly better, once the next search (after
  // another reacquire_after_s) has found the same place.
  double min_explained_share = 0.0;
  double min_share_drop = 0.05;
  double reacquire_after_s = 1.0;
  double reacquire_max_radius_m = 2.0;
  // The local search runs a slice of about this much work between scans
  // (GlobalSearch; a unit is one point looked up, about 10 ns), so that a
  // lost tracker keeps its pace; it searches the scan it started with, and
  // what it finds is carried to the newest scan by odometry.
  int search_work_per_scan = 60000;
  void Validate() const;
  // The covariance of a given initial pose (from the initial sigmas).
  Eigen::Matrix3d InitialCovariance() const;
};

// Why an input was not used. The counters in TrackerStats are indexed by it.
enum class Rejection {
  kEmptyScan,
  kBeamCountMismatch,
  kBadScanGeometry,
  kScanOutOfOrder,
  kScanInFuture,
  kNoOdometry,
  kNoInitialPose,
  kOdometryNonFinite,
  kOdometryOutOfOrder,
  kOdometryJump,
  kInitialPoseInvalid,
  kScanTooLong,
  kTooManyBeams,
  kLocaliserRejected,
  kCount
};
const char* ToString(Rejection r);

struct TrackerStats {
  std::array<uint64_t, static_cast<size_t>(Rejection::kCount)> rejected{};
  uint64_t scans_processed = 0;
  uint64_t scans_lost = 0;
  uint64_t scans_not_deskewed = 0;   // processed although odometry did not cover every beam
  uint64_t corrections_refused = 0;  // by the whole-scan check
  uint64_t reacquisitions = 0;       // local searches that moved the pose
  // Visibilities computed (VisibilityCache), and updates that used the one of
  // the place before because the place they needed was not computed yet.
  uint64_t visibility_computations = 0;
  uint64_t stale_visibility_updates = 0;
  uint64_t Rejected() const;
};

// One scan as it arrives (LaserScan fields); `declared_count` is the number of
// beams the geometry implies ((angle_max - angle_min) / increment + 1).
struct ScanInput {
  double stamp = 0.0;
  double angle_min = 0.0, angle_max = 0.0, angle_increment = 0.0, time_increment = 0.0;
  double range_min = 0.0, range_max = 0.0;
  const float* ranges = nullptr;
  size_t count = 0;
};

struct TrackedPose {
  double stamp = 0.0;
  geometry::Pose2D pose;  // robot base, map frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

class PoseTracker {
 public:
  PoseTracker(const world_model::WorldModel& world, const LocaliserOptions& localiser_options,
              const TrackerOptions& options);

  // Odometry of the robot base in the odom frame.
  std::optional<Rejection> AddOdometry(double stamp, const geometry::Pose2D& odom_pose);
  // A map-frame pose at `stamp` (uses the odometry at or before that time).
  std::optional<Rejection> SetInitialPose(double stamp, const geometry::Pose2D& pose,
                                          const Eigen::Matrix3d& covariance);
  bool HasInitialPose() const { return initialised_; }
  // Drops the pose (the robot was carried away): scans are refused until a new
  // initial pose; odometry and the calibration learnt so far stay.
  // Also drops what a search before it found (re-acquisition starts afresh).
  void ForgetPose();

  enum class ScanVerdict { kProcessed, kWaitForOdometry, kRejected };
  struct ScanOutcome {
    ScanVerdict verdict = ScanVerdict::kRejected;
    Rejection rejection = Rejection::kEmptyScan;  // when kRejected
    const char* detail = nullptr;                 // the localiser's own reason, if any
    const LocalisationResult* result = nullptr;   // when kProcessed
    TrackedPose pose;                             // when kProcessed
    // The tracker's verdict (when kProcessed): lost when the scan contradicts
    // the tracked pose (correction beyond the gates, solver failure) or when,
    // without a usable scan, the position sigma has grown past lost_sigma_m.
    // Coasting on odometry within that bound, or correcting only the
    // directions the scan pins, is not lost.
    bool lost = false;
    const char* lost_reason = "";
    int pinned_directions = 0;    // directions this scan corrected (0..3)
    double explained_share = -1;  // whole-scan check at the tracked pose (-1: not checked)
    bool reacquired = false;      // a local search moved the pose (jump: by how much)
    geometry::Pose2D jump;
    double check_us = 0.0;   // the whole-scan check's time
    double search_us = 0.0;  // the local search's, when one ran
  };
  // `waited_s`: how long the scan has already waited for odometry.
  ScanOutcome ProcessScan(const ScanInput& scan, double waited_s);

  // Between scans, off the path from scan to pose: prepares the localiser
  // for the next scan at the newest pose (Localiser::Anticipate) and runs a
  // slice of a local search under way (its result is applied at the next
  // scan once it is done).
  void Anticipate();

  // The map -> odom correction and the pose carried forward to the newest odometry.
  geometry::Pose2D MapToOdom() const { return map_to_odom_; }
  std::optional<TrackedPose> Latest() const;
  // The odometry calibration learnt so far: distance scale, turn scale, heading
  // drift (rad per metre driven).
  Eigen::Vector3d OdometryCalibration() const { return filter_.Calibration(); }
  TrackerStats Stats() const;
  const OdometryHistory& Odometry() const { return history_; }
  const LocaliserOptions& Options() const { return localiser_.Options(); }

 private:
  ScanOutcome Reject(Rejection r, const char* detail = nullptr);
  // What the scan's own geometry and its place in time refuse it for, if anything.
  std::optional<Rejection> ScanProblem(const ScanInput& scan) const;
  // The localiser's input: the scan and the filter's prior (de-skewed by
  // motion_ when `deskew`).
  UpdateInput PriorInput(const ScanInput& scan, bool deskew) const;
  // The whole-scan check of the localiser's correction of `prior`: the share
  // of the scan the map explains at the pose kept, and whether the
  // correction is refused for explaining clearly less.
  double CheckCorrection(const ScanInput& scan, const geometry::Pose2D& prior,
                         const LocalisationResult& r, bool* refused);
  // The lost verdict: the localiser contradicted, or nothing pinned the pose
  // while its spread grew beyond lost_sigma_m.
  void JudgeLost(const LocalisationResult& r, const Eigen::Matrix3d& covariance, ScanOutcome& out);
  // Fuses a localised scan into the filter; returns the directions corrected.
  int Correct(const LocalisationResult& r, const UpdateInput& in, const geometry::Pose2D& odom);
  // The whole-scan check's points (laser frame) of this scan, and their share
  // explained by the map at robot pose `pose` (each beam traced through the
  // map at the first pose asked about, the prior).
  void CollectCheckPoints(const ScanInput& scan);
  double ExplainedShare(const geometry::Pose2D& pose);
  // Below min_explained_share for long enough: a local search, a slice per
  // scan, and the filter reset where it finds the scan explained.
  void Reacquire(const ScanInput& scan, ScanOutcome& out);
  // The finished search's result applied (or not) to the tracked pose.
  void ApplySearch(const GlobalResult& found, ScanOutcome& out);

  Localiser localiser_;
  TrackerOptions options_;
  OdometryHistory history_;
  BeamMotion motion_;
  bool initialised_ = false;
  OdometryFilter filter_;  // pose at odom_at_last_update_, with calibration
  geometry::Pose2D map_to_odom_;
  geometry::Pose2D odom_at_last_update_;
  geometry::Pose2D odom_at_last_correction_;  // for min_update_travel_m
  bool corrected_ = false;
  std::unique_ptr<GlobalLocaliser> search_;  // whole-scan check and re-acquisition
  std::vector<Eigen::Vector2d> check_points_;
  std::vector<GlobalLocaliser::BeamVerdict> check_verdicts_;
  // The unit directions of the beams the check uses, for the scan geometry
  // they were computed for.
  struct CheckGeometry {
    size_t count = 0;
    double angle_min = 0.0, angle_increment = 0.0;
  };
  CheckGeometry check_geometry_;
  std::vector<Eigen::Vector2d> check_directions_;
  double low_share_since_ = -1.0;  // stamp the share fell below min_explained_share, or -1
  // The map -> odom correction the last search found, waiting for the next
  // search to find it again before the tracker jumps there.
  std::optional<geometry::Pose2D> pending_correction_;
  // The search under way: the points of the scan it started with, the
  // odometry there and the share the tracked pose explained of them.
  std::optional<GlobalSearch> search_task_;
  std::vector<Eigen::Vector2d> search_points_;
  geometry::Pose2D search_odometry_;
  double search_share_ = 0.0;
  double search_stamp_ = 0.0;
  double last_scan_stamp_ = -1e300;
  TrackerStats stats_;
};

}  // namespace structloc::localisation_core
