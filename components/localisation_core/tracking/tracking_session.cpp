// Tracking session (see header).
#include "structloc/localisation_core/tracking/tracking_session.hpp"

#include <algorithm>
#include <chrono>

namespace structloc::localisation_core {

TrackingSession::TrackingSession(const world_model::WorldModel* world,
                                 const LocaliserOptions& localiser_options,
                                 const SessionOptions& options, Scheduling scheduling)
    : options_(options), scheduling_(scheduling) {
  options_.Validate();
  if (world != nullptr) {
    tracker_ = std::make_unique<PoseTracker>(*world, localiser_options, options_.tracker);
  }
}

void TrackingSession::ExpectInitialPose(const geometry::Pose2D& pose, InitialPoseWhen when) {
  pending_pose_ = PendingPose{pose, options_.tracker.InitialCovariance(), false, when};
}

void TrackingSession::ResumeFrom(const SessionState& saved) {
  const Eigen::Vector3d variance =
      saved.variance.cwiseMax(options_.tracker.InitialCovariance().diagonal());
  pending_pose_ = PendingPose{saved.map_to_odom, Eigen::Matrix3d(variance.asDiagonal()), true,
                              InitialPoseWhen::kAtFirstOdometry};
}

void TrackingSession::ForgetPose() {
  if (tracker_) tracker_->ForgetPose();
  pending_pose_.reset();
}

bool TrackingSession::WaitingForInitialPose() const {
  return tracker_ && !tracker_->HasInitialPose() && !pending_pose_;
}

void TrackingSession::NoteProblem(const std::string& problem, double now) {
  last_problem_ = problem;
  last_problem_s_ = now;
}

std::optional<std::pair<std::string, double>> TrackingSession::LastProblem(double now,
                                                                           double hold_s) const {
  if (last_problem_.empty() || now - last_problem_s_ > hold_s) return std::nullopt;
  return std::make_pair(last_problem_, now - last_problem_s_);
}

bool TrackingSession::AddOdometry(double stamp, const geometry::Pose2D& pose, double now) {
  // The scheduling's own record of what arrived, also of what the tracker refuses.
  if (!newest_odometry_ || stamp > newest_odometry_->stamp) {
    newest_odometry_ = StampedOdometry{stamp, pose};
    if (scheduling_ == Scheduling::kInOrder) odometry_log_.push_back({stamp, pose});
  }
  if (tracker_) {
    if (auto r = tracker_->AddOdometry(stamp, pose)) {
      NoteProblem(std::string("odometry rejected: ") + ToString(*r), now);
      return false;
    }
  }
  ApplyPendingAtOdometry(stamp, pose, now);
  return true;
}

void TrackingSession::ApplyPendingAtOdometry(double stamp, const geometry::Pose2D& odom,
                                             double now) {
  if (!tracker_ || !pending_pose_ || pending_pose_->when != InitialPoseWhen::kAtFirstOdometry) {
    return;
  }
  const PendingPose pending = *pending_pose_;
  pending_pose_.reset();
  if (tracker_->HasInitialPose()) return;
  const geometry::Pose2D pose =
      pending.is_correction ? geometry::Compose(pending.pose, odom) : pending.pose;
  if (auto r = tracker_->SetInitialPose(stamp, pose, pending.covariance)) {
    NoteProblem(std::string("initial pose rejected: ") + ToString(*r), now);
  }
}

TrackingSession::InitialPoseOutcome TrackingSession::SetInitialPose(const InitialPoseInput& in,
                                                                    const std::string& source,
                                                                    double now) {
  if (!tracker_) return InitialPoseOutcome::kRejected;
  if (auto r = tracker_->SetInitialPose(in.stamp, in.pose, in.covariance)) {
    if (*r == Rejection::kNoOdometry) {
      // Valid (SetInitialPose checks that first): applied at the first odometry.
      pending_pose_ = PendingPose{in.pose, in.covariance, false, InitialPoseWhen::kAtFirstOdometry};
      return InitialPoseOutcome::kPending;
    }
    NoteProblem("initial pose on " + source + " rejected: " + ToString(*r), now);
    return InitialPoseOutcome::kRejected;
  }
  return InitialPoseOutcome::kSet;
}

void TrackingSession::AddScan(SessionScan scan, double now) {
  if (scheduling_ == Scheduling::kNewestWins && !waiting_.empty()) {
    ++dropped_;  // overload: the newest scan wins
    waiting_.clear();
  }
  waiting_.push_back({std::move(scan), now});
}

size_t TrackingSession::Apply(SessionInputs& inputs, const std::string& initial_pose_source) {
  for (const auto& o : inputs.odometry) AddOdometry(o.stamp, o.pose, inputs.scan_arrived_s);
  size_t accepted = 0;
  for (const auto& p : inputs.initial_poses) {
    if (SetInitialPose(p, initial_pose_source, inputs.scan_arrived_s) !=
        InitialPoseOutcome::kRejected) {
      ++accepted;
    }
  }
  dropped_ += inputs.dropped;
  if (inputs.scan) AddScan(std::move(*inputs.scan), inputs.scan_arrived_s);
  return accepted;
}

bool TrackingSession::OdometryReaches(double t) const {
  if (scheduling_ == Scheduling::kNewestWins) {
    return tracker_ && !tracker_->Odometry().Empty() && t >= tracker_->Odometry().Oldest();
  }
  return !odometry_log_.empty() && t >= odometry_log_.front().stamp;
}

bool TrackingSession::OdometryCovers(double t) const {
  if (scheduling_ == Scheduling::kNewestWins) {
    return OdometryReaches(t) && t <= tracker_->Odometry().Newest();
  }
  return OdometryReaches(t) && t <= odometry_log_.back().stamp;
}

std::optional<geometry::Pose2D> TrackingSession::OdometryAt(double t) const {
  if (scheduling_ == Scheduling::kNewestWins) {
    if (!tracker_ || tracker_->Odometry().Empty()) return std::nullopt;
    const auto& h = tracker_->Odometry();
    return h.At(std::min(std::max(t, h.Oldest()), h.Newest()));
  }
  const auto& log = odometry_log_;
  if (log.empty() || t < log.front().stamp) return std::nullopt;
  auto it = std::lower_bound(log.begin(), log.end(), t,
                             [](const StampedOdometry& p, double s) { return p.stamp < s; });
  if (it == log.end()) return log.back().pose;
  if (it == log.begin() || it->stamp == t) return it->pose;
  const auto& a = *(it - 1);
  return geometry::Interpolate(a.pose, it->pose, (t - a.stamp) / (it->stamp - a.stamp));
}

ScanReport TrackingSession::Rejected(const WaitingScan& waiting, Rejection r, const char* detail) {
  ScanReport report;
  report.kind = ScanReport::Kind::kRejected;
  report.stamp = waiting.scan.geometry.stamp;
  report.rejection = r;
  report.reason = std::string(ToString(r)) + (detail != nullptr ? std::string(": ") + detail : "");
  return report;
}

std::optional<ScanReport> TrackingSession::Next(double now, bool end_of_input) {
  if (waiting_.empty()) return std::nullopt;
  const WaitingScan& front = waiting_.front();
  double waited = now - front.arrived_s;
  if (scheduling_ == Scheduling::kInOrder) {
    // Offline, a scan waits for the odometry that covers it, not for a clock.
    const bool overdue = waiting_.size() > options_.max_pending_scans;
    const bool covered = newest_odometry_ && newest_odometry_->stamp >= front.scan.LastBeamStamp();
    if (!end_of_input && !overdue && !covered) return std::nullopt;
    waited = 1e9;
  }
  bool wait = false;
  ScanReport report = Process(front, waited, &wait);
  if (wait) return std::nullopt;
  if (scheduling_ == Scheduling::kInOrder) now = front.scan.geometry.stamp;
  if (report.kind == ScanReport::Kind::kRejected) {
    NoteProblem("scan rejected: " + report.reason, now);
  }
  if (report.kind == ScanReport::Kind::kTracked) {
    const auto& r = *report.result;
    if (report.lost) {
      if (!lost_) {
        ++lost_periods_;
        lost_since_ = now;
      } else {
        lost_seconds_ += now - last_processed_s_;
        longest_lost_s_ = std::max(longest_lost_s_, now - lost_since_);
      }
    }
    lost_ = report.lost;
    lost_reason_ = report.lost_reason;
    last_quality_ = r.quality;
    last_processed_s_ = now;
  }
  report.scan = std::move(waiting_.front().scan);
  waiting_.pop_front();
  return report;
}

ScanReport TrackingSession::Process(const WaitingScan& waiting, double waited_s, bool* wait) {
  const SessionScan& scan = waiting.scan;
  std::optional<geometry::Pose2D> odom = scan.odometry;
  if (scheduling_ == Scheduling::kInOrder && !odom) odom = OdometryAt(scan.geometry.stamp);
  if (!tracker_) {
    // Nothing to track: only what the scan itself must satisfy.
    if (!odom) return Rejected(waiting, Rejection::kNoOdometry);
    if (scan.ranges.empty() || scan.geometry.angle_increment == 0.0) {
      auto report = Rejected(waiting, Rejection::kEmptyScan);
      report.odometry = odom;
      return report;
    }
    if (!(scan.geometry.stamp > last_untracked_stamp_)) {
      auto report = Rejected(waiting, Rejection::kScanOutOfOrder);
      report.odometry = odom;
      return report;
    }
    last_untracked_stamp_ = scan.geometry.stamp;
    ScanReport report;
    report.kind = ScanReport::Kind::kUntracked;
    report.stamp = scan.geometry.stamp;
    report.odometry = *odom;
    return report;
  }
  if (scheduling_ == Scheduling::kInOrder) {
    if (!odom) return Rejected(waiting, Rejection::kNoOdometry);
    if (pending_pose_ && pending_pose_->when == InitialPoseWhen::kAtFirstScan) {
      // The log's initial pose is that of its first laser line.
      if (auto r = tracker_->SetInitialPose(scan.geometry.stamp, pending_pose_->pose,
                                            pending_pose_->covariance)) {
        // Said once; every later scan is then rejected as having no initial pose.
        NoteProblem(std::string("initial pose rejected: ") + ToString(*r), waiting.arrived_s);
      }
      pending_pose_.reset();
    }
  }
  const double cpu0 = ThreadCpuMicroseconds();
  const auto t0 = std::chrono::steady_clock::now();
  const auto outcome = tracker_->ProcessScan(scan.View(), waited_s);
  const double update_us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  const double update_cpu_us = ThreadCpuMicroseconds() - cpu0;
  if (outcome.verdict == PoseTracker::ScanVerdict::kWaitForOdometry) {
    *wait = true;
    return {};
  }
  if (outcome.verdict == PoseTracker::ScanVerdict::kRejected) {
    auto report = Rejected(waiting, outcome.rejection, outcome.detail);
    report.odometry = odom;
    report.update_us = update_us;
    return report;
  }
  ScanReport report;
  report.kind = ScanReport::Kind::kTracked;
  report.stamp = scan.geometry.stamp;
  report.result = outcome.result;
  report.pose = outcome.pose;
  report.lost = outcome.lost;
  report.lost_reason = outcome.lost_reason;
  report.reacquired = outcome.reacquired;
  report.jump = outcome.jump;
  report.odometry = odom;
  report.update_us = update_us;
  const auto& times = outcome.result->times;
  auto& t = report.timings;
  t[Stage::kPrefilter] = times.prefilter_us;
  t[Stage::kExpectation] = times.expectation_us;
  t[Stage::kLineFit] = times.line_fit_us;
  t[Stage::kExtraction] = outcome.result->ExtractUs();
  t[Stage::kSolve] = times.solve_us;
  t[Stage::kCheck] = outcome.check_us;
  t[Stage::kSearch] = outcome.search_us;
  t.total_us = update_us;
  t.total_cpu_us = update_cpu_us;
  return report;
}

void TrackingSession::Anticipate() {
  const double cpu0 = ThreadCpuMicroseconds();
  const auto t0 = std::chrono::steady_clock::now();
  if (tracker_ && tracker_->HasInitialPose()) tracker_->Anticipate();
  anticipate_us_ =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  anticipate_cpu_us_ = ThreadCpuMicroseconds() - cpu0;
}

std::optional<TrackedPose> TrackingSession::Latest() const {
  if (!tracker_) return std::nullopt;
  return tracker_->Latest();
}

TrackerStats TrackingSession::Stats() const {
  return tracker_ ? tracker_->Stats() : TrackerStats{};
}

std::optional<SessionState> TrackingSession::StateToSave(double now) {
  const auto latest = Latest();
  if (!latest) return std::nullopt;
  if (last_state_save_s_ && now - *last_state_save_s_ < options_.state_period_s) {
    return std::nullopt;
  }
  last_state_save_s_ = now;
  return SessionState{tracker_->MapToOdom(), latest->covariance.diagonal()};
}

}  // namespace structloc::localisation_core
