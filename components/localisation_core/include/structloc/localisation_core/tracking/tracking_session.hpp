// One tracking session around the PoseTracker, DDS-free and single-threaded,
// used alike by the localisation component (live, wall-clock `now`) and the
// offline replay (log time): it holds the policy both share, so that the
// components only convert and move messages.
//  - Scheduling: live, one scan slot in which the newest scan wins (dropped
//    ones counted) and a scan waits for odometry at most odometry_wait_s;
//    replay, scans in order, each waiting until odometry covers its last beam
//    (or the input ends, or max_pending_scans wait).
//  - Odometry buffering, and the odometry pose at a scan's time (OdometryAt).
//  - The initial-pose state machine: a pose given at start-up (applied at the
//    first odometry sample, or at the first scan for a log whose initial pose
//    is that of its first laser line), a saved map -> odom correction to
//    resume from, and initial poses arriving before any odometry.
//  - Lost timers (since when, how many periods, for how long), when the pose
//    is due to be saved, and the newest rejected input as a sentence.
// Without a world model (replay --no-map) nothing is tracked: scans are
// scheduled, checked and handed back with their odometry pose.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "structloc/localisation_core/localiser/stage_timings.hpp"
#include "structloc/localisation_core/scan/session_scan.hpp"
#include "structloc/localisation_core/tracking/pose_tracker.hpp"
#include "structloc/localisation_core/tracking/session_inbox.hpp"
#include "structloc/localisation_core/tracking/tracking_session_options.hpp"

namespace structloc::localisation_core {

enum class Scheduling {
  kNewestWins,  // live: one slot, waits bounded by odometry_wait_s
  kInOrder,     // offline: every scan, in order, once odometry covers it
};

// What became of one scan.
struct ScanReport {
  enum class Kind { kTracked, kRejected, kUntracked };
  Kind kind = Kind::kRejected;
  SessionScan scan;  // the scan itself, handed back
  double stamp = 0.0;
  Rejection rejection = Rejection::kEmptyScan;  // when kRejected
  std::string reason;                           // when kRejected: the sentence to show
  const LocalisationResult* result = nullptr;   // when kTracked (valid until the next scan)
  TrackedPose pose;                             // when kTracked
  bool lost = false;                            // when kTracked: the tracker's verdict
  const char* lost_reason = "";                 // (PoseTracker::ScanOutcome)
  bool reacquired = false;                      // a local search moved the pose by `jump`
  geometry::Pose2D jump;
  // In-order scheduling: the odometry pose at the scan, when there was one
  // (then the scan also went through the tracker, if tracking, and update_us
  // is its time there).
  std::optional<geometry::Pose2D> odometry;
  double update_us = 0.0;
  StageTimings timings;  // when kTracked: stage by stage, and the update's CPU time
};

// A saved correction: the map -> odom transform and the pose's variances.
struct SessionState {
  geometry::Pose2D map_to_odom;
  Eigen::Vector3d variance;
};

class TrackingSession {
 public:
  // `world` may be null (nothing tracked); it must outlive the session.
  TrackingSession(const world_model::WorldModel* world, const LocaliserOptions& localiser_options,
                  const SessionOptions& options, Scheduling scheduling);

  enum class InitialPoseWhen { kAtFirstOdometry, kAtFirstScan };
  // A pose given at start-up, with the options' initial covariance.
  void ExpectInitialPose(const geometry::Pose2D& pose, InitialPoseWhen when);
  // Resumes from a saved correction at the first odometry sample; its
  // variances are never trusted more than a freshly given initial pose.
  void ResumeFrom(const SessionState& saved);
  // Drops the current pose and any pending one: the session waits for a new
  // initial pose (a request to relocalise globally).
  void ForgetPose();

  // Inputs; `now` is the caller's clock. Returns false when it was refused
  // (the reason becomes LastProblem()).
  bool AddOdometry(double stamp, const geometry::Pose2D& odom_pose, double now);
  enum class InitialPoseOutcome { kSet, kPending, kRejected };
  // `source` names where it came from in the problem sentence.
  InitialPoseOutcome SetInitialPose(const InitialPoseInput& pose, const std::string& source,
                                    double now);
  void AddScan(SessionScan scan, double now);
  // Everything an inbox collected, in the order odometry, initial poses, scan.
  // Returns how many of its initial poses were accepted: set, or held until
  // the first odometry sample when none has come yet.
  size_t Apply(SessionInputs& inputs, const std::string& initial_pose_source);

  // The next scan that is ready, processed; nullopt when none is (yet).
  // `end_of_input`: no more odometry will come, process what waits. In
  // in-order scheduling the lost timers run on the scans' stamps, not `now`.
  std::optional<ScanReport> Next(double now, bool end_of_input = false);

  // Between scans, after their poses are out: the work the next scan would
  // otherwise wait for (which features are visible where it will be taken)
  // and a slice of a local search under way (PoseTracker::Anticipate).
  void Anticipate();
  // The last Anticipate's wall and thread CPU time.
  double LastAnticipateUs() const { return anticipate_us_; }
  double LastAnticipateCpuUs() const { return anticipate_cpu_us_; }

  // The odometry pose at `t` from what has arrived (interpolated; the newest
  // beyond it); nullopt before the first sample.
  std::optional<geometry::Pose2D> OdometryAt(double t) const;
  // Whether odometry from `t` or before has arrived. A component's first
  // scans can be older than its first odometry (its readers match one by one),
  // and a pose found in such a scan must not be tied to later odometry.
  bool OdometryReaches(double t) const;
  // Whether odometry from `t` or before and from `t` or after has arrived, so
  // that OdometryAt(t) interpolates rather than holds the newest sample.
  bool OdometryCovers(double t) const;

  // The correction to save when saving is due at `now` (then counted as saved).
  std::optional<SessionState> StateToSave(double now);

  bool Tracking() const { return tracker_ != nullptr; }
  bool HasInitialPose() const { return tracker_ && tracker_->HasInitialPose(); }
  bool WaitingForInitialPose() const;
  const PoseTracker* Tracker() const { return tracker_.get(); }
  std::optional<TrackedPose> Latest() const;
  TrackerStats Stats() const;
  uint64_t Dropped() const { return dropped_; }
  const SessionOptions& Options() const { return options_; }

  bool Lost() const { return lost_; }
  double LostFor(double now) const { return lost_ ? now - lost_since_ : 0.0; }
  bool LostTooLong(double now) const { return LostFor(now) > options_.lost_error_after_s; }
  const std::string& LostReason() const { return lost_reason_; }
  size_t LostPeriods() const { return lost_periods_; }
  double LostSeconds() const { return lost_seconds_; }
  double LongestLostSeconds() const { return longest_lost_s_; }  // one period, the longest
  double LastQuality() const { return last_quality_; }

  // The newest refused input as a sentence ("scan rejected: ..."), if it came
  // within `hold_s` of `now`, and how long ago.
  std::optional<std::pair<std::string, double>> LastProblem(double now, double hold_s) const;
  void NoteProblem(const std::string& problem, double now);

 private:
  struct WaitingScan {
    SessionScan scan;
    double arrived_s;
  };
  ScanReport Rejected(const WaitingScan& waiting, Rejection r, const char* detail = nullptr);
  ScanReport Process(const WaitingScan& waiting, double waited_s, bool* wait);
  void ApplyPendingAtOdometry(double stamp, const geometry::Pose2D& odom, double now);

  SessionOptions options_;
  Scheduling scheduling_;
  std::unique_ptr<PoseTracker> tracker_;
  std::deque<WaitingScan> waiting_;
  uint64_t dropped_ = 0;
  std::vector<StampedOdometry> odometry_log_;  // kInOrder: everything, for OdometryAt
  std::optional<StampedOdometry> newest_odometry_;

  struct PendingPose {
    geometry::Pose2D pose;  // a map pose, or the map -> odom correction
    Eigen::Matrix3d covariance;
    bool is_correction = false;
    InitialPoseWhen when = InitialPoseWhen::kAtFirstOdometry;
  };
  std::optional<PendingPose> pending_pose_;

  double last_untracked_stamp_ = -1e300;
  bool lost_ = false;
  double lost_since_ = 0.0;
  double last_processed_s_ = 0.0;
  size_t lost_periods_ = 0;
  double lost_seconds_ = 0.0;
  double longest_lost_s_ = 0.0;
  std::string lost_reason_;
  double last_quality_ = 0.0;
  std::optional<double> last_state_save_s_;
  std::string last_problem_;
  double last_problem_s_ = 0.0;
  double anticipate_us_ = 0.0;
  double anticipate_cpu_us_ = 0.0;
};

}  // namespace structloc::localisation_core
