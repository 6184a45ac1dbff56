// Pose tracking around the Localiser (see header).
#include "structloc/localisation_core/tracking/pose_tracker.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace structloc::localisation_core {

const char* ToString(Rejection r) {
  switch (r) {
    case Rejection::kEmptyScan:
      return "empty scan";
    case Rejection::kBeamCountMismatch:
      return "beam count does not match the scan angles";
    case Rejection::kBadScanGeometry:
      return "angle_increment zero or non-finite, or bad limits";
    case Rejection::kScanOutOfOrder:
      return "scan stamp not after the previous scan";
    case Rejection::kScanInFuture:
      return "scan stamp too far ahead of the odometry";
    case Rejection::kNoOdometry:
      return "no odometry at the scan's time";
    case Rejection::kNoInitialPose:
      return "no initial pose yet";
    case Rejection::kOdometryNonFinite:
      return "odometry pose or stamp not finite, or its orientation not a unit quaternion";
    case Rejection::kOdometryOutOfOrder:
      return "odometry stamp not after the previous one";
    case Rejection::kOdometryJump:
      return "odometry jump faster than max_odometry_speed_m_s or max_odometry_turn_rate_rad_s";
    case Rejection::kInitialPoseInvalid:
      return "initial pose not finite or its covariance not symmetric positive definite";
    case Rejection::kScanTooLong:
      return "time_increment x beams longer than max_scan_duration_s";
    case Rejection::kTooManyBeams:
      return "more beams than max_beams";
    case Rejection::kLocaliserRejected:
      return "rejected by the localiser";
    case Rejection::kCount:
      break;
  }
  return "unknown";
}

Eigen::Matrix3d TrackerOptions::InitialCovariance() const {
  const double xy = initial_sigma_xy_m * initial_sigma_xy_m;
  return Eigen::Vector3d(xy, xy, initial_sigma_theta_rad * initial_sigma_theta_rad).asDiagonal();
}

TrackerStats PoseTracker::Stats() const {
  TrackerStats stats = stats_;
  stats.visibility_computations = localiser_.VisibilityComputations();
  stats.stale_visibility_updates = localiser_.StaleVisibilityUpdates();
  return stats;
}

uint64_t TrackerStats::Rejected() const {
  uint64_t n = 0;
  for (auto c : rejected) n += c;
  return n;
}

namespace {
double MicrosecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
      .count();
}

// Two searches that arrive at corrections this close agree.
constexpr double kSameCorrectionM = 0.2;
constexpr double kSameCorrectionRad = 0.087;  // 5 deg

OdometryFilterOptions FilterOptions(const TrackerOptions& o) {
  OdometryFilterOptions f;
  f.sigma_xy_per_m = o.odometry_sigma_xy_per_m;
  f.sigma_theta_per_m = o.odometry_sigma_theta_per_m;
  f.sigma_theta_per_rad = o.odometry_sigma_theta_per_rad;
  f.scale_sigma = o.odometry_scale_sigma;
  f.drift_sigma_rad_per_m = o.odometry_drift_sigma_rad_per_m;
  f.calibration_walk_per_m = o.calibration_walk_per_m;
  f.weak_std_m = o.weak_std_m;
  f.weak_std_rad = o.weak_std_rad;
  return f;
}
}  // namespace

PoseTracker::PoseTracker(const world_model::WorldModel& world,
                         const LocaliserOptions& localiser_options, const TrackerOptions& options)
    : localiser_(world, localiser_options),
      options_(options),
      history_(4096),
      filter_(FilterOptions(options)) {
  if (options_.min_explained_share > 0.0) {
    search_ = std::make_unique<GlobalLocaliser>(world, GlobalLocaliserOptions{});
    check_points_.reserve(2 * static_cast<size_t>(search_->Options().max_points) + 1);
    check_directions_.reserve(2 * static_cast<size_t>(search_->Options().max_points) + 1);
    check_verdicts_.reserve(2 * static_cast<size_t>(search_->Options().max_points) + 1);
  }
  options_.Validate();
  motion_.Reserve(static_cast<size_t>(localiser_options.max_beams));
}

PoseTracker::ScanOutcome PoseTracker::Reject(Rejection r, const char* detail) {
  ++stats_.rejected[static_cast<size_t>(r)];
  ScanOutcome out;
  out.verdict = ScanVerdict::kRejected;
  out.rejection = r;
  out.detail = detail;
  return out;
}

namespace {
// A covariance a Gaussian can have: finite, symmetric, positive definite.
bool IsSymmetricPositiveDefinite(const Eigen::Matrix3d& c) {
  if (!c.allFinite()) return false;
  const double scale = c.cwiseAbs().maxCoeff();
  if (!((c - c.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * scale)) return false;
  const Eigen::LLT<Eigen::Matrix3d> llt(0.5 * (c + c.transpose()));
  return llt.info() == Eigen::Success &&
         (llt.matrixL().toDenseMatrix().diagonal().array() > 0).all();
}
}  // namespace

std::optional<Rejection> PoseTracker::AddOdometry(double stamp, const geometry::Pose2D& pose) {
  auto reject = [this](Rejection r) {
    ++stats_.rejected[static_cast<size_t>(r)];
    return r;
  };
  if (!std::isfinite(stamp) || !geometry::IsFinite(pose))
    return reject(Rejection::kOdometryNonFinite);
  if (!history_.Empty()) {
    if (!(stamp > history_.Newest())) return reject(Rejection::kOdometryOutOfOrder);
    const auto last = history_.At(history_.Newest());
    const double dt = stamp - history_.Newest();
    const double step_dt = std::max(dt, 0.01);
    if ((pose.Translation() - last->Translation()).norm() >
            options_.max_odometry_speed_m_s * step_dt ||
        std::abs(geometry::WrapAngle(pose.theta - last->theta)) >
            options_.max_odometry_turn_rate_rad_s * step_dt) {
      return reject(Rejection::kOdometryJump);
    }
  }
  history_.Add(stamp, pose);
  return std::nullopt;
}

std::optional<Rejection> PoseTracker::SetInitialPose(double stamp, const geometry::Pose2D& pose,
                                                     const Eigen::Matrix3d& covariance) {
  if (!geometry::IsFinite(pose) || !IsSymmetricPositiveDefinite(covariance)) {
    ++stats_.rejected[static_cast<size_t>(Rejection::kInitialPoseInvalid)];
    return Rejection::kInitialPoseInvalid;
  }
  if (history_.Empty()) {
    ++stats_.rejected[static_cast<size_t>(Rejection::kNoOdometry)];
    return Rejection::kNoOdometry;
  }
  const double t = std::min(std::max(stamp, history_.Oldest()), history_.Newest());
  const geometry::Pose2D odom = *history_.At(t);
  map_to_odom_ = geometry::Compose(pose, geometry::Inverse(odom));
  odom_at_last_update_ = odom;
  filter_.Reset(pose, covariance);
  corrected_ = false;
  initialised_ = true;
  // A search before this pose was given must neither hurry nor confirm the next one.
  low_share_since_ = -1.0;
  pending_correction_.reset();
  search_task_.reset();
  return std::nullopt;
}

void PoseTracker::ForgetPose() {
  initialised_ = false;
  low_share_since_ = -1.0;
  pending_correction_.reset();
  search_task_.reset();
}

void PoseTracker::Anticipate() {
  if (const auto latest = Latest()) localiser_.Anticipate(latest->pose);
  if (search_task_ && !search_task_->Done()) {
    search_task_->Advance(static_cast<uint64_t>(options_.search_work_per_scan));
  }
}

std::optional<TrackedPose> PoseTracker::Latest() const {
  if (!initialised_ || history_.Empty()) return std::nullopt;
  const geometry::Pose2D odom = *history_.At(history_.Newest());
  return TrackedPose{history_.Newest(), geometry::Compose(map_to_odom_, odom),
                     filter_.PoseCovariance()};
}

std::optional<Rejection> PoseTracker::ScanProblem(const ScanInput& scan) const {
  if (scan.count == 0 || scan.ranges == nullptr) return Rejection::kEmptyScan;
  if (!std::isfinite(scan.angle_increment) || scan.angle_increment == 0.0 ||
      !std::isfinite(scan.angle_min) || !std::isfinite(scan.stamp) ||
      !std::isfinite(scan.time_increment) || scan.time_increment < 0) {
    return Rejection::kBadScanGeometry;
  }
  if (scan.time_increment * static_cast<double>(scan.count) > options_.max_scan_duration_s) {
    return Rejection::kScanTooLong;
  }
  if (scan.count > static_cast<size_t>(localiser_.Options().max_beams)) {
    return Rejection::kTooManyBeams;
  }
  if (std::isfinite(scan.angle_max)) {
    const double implied = (scan.angle_max - scan.angle_min) / scan.angle_increment + 1.0;
    if (std::abs(implied - static_cast<double>(scan.count)) > 1.01) {
      return Rejection::kBeamCountMismatch;
    }
  }
  if (!(scan.stamp > last_scan_stamp_)) return Rejection::kScanOutOfOrder;
  if (history_.Empty()) return Rejection::kNoOdometry;
  if (scan.stamp > history_.Newest() + options_.max_future_s) return Rejection::kScanInFuture;
  if (!initialised_) return Rejection::kNoInitialPose;
  return std::nullopt;
}

UpdateInput PoseTracker::PriorInput(const ScanInput& scan, bool deskew) const {
  UpdateInput in;
  in.scan.ranges = scan.ranges;
  in.scan.count = scan.count;
  in.scan.angle_min = scan.angle_min;
  in.scan.angle_increment = scan.angle_increment;
  in.scan.time_increment = scan.time_increment;
  in.scan.range_min = scan.range_min;
  in.scan.range_max = scan.range_max;
  in.odometry_pose = filter_.Pose();
  in.odometry_covariance = filter_.PoseCovariance();
  in.motion = deskew ? &motion_ : nullptr;
  return in;
}

double PoseTracker::CheckCorrection(const ScanInput& scan, const geometry::Pose2D& prior,
                                    const LocalisationResult& r, bool* refused) {
  CollectCheckPoints(scan);
  // The correction must not make the map explain less of the scan. Below a
  // centimetre and a quarter of a degree the scan cannot tell: checked once.
  double share = ExplainedShare(prior);
  const bool usable = !r.lost || r.lost_reason == LostReason::kUnderdetermined;
  const geometry::Pose2D moved = geometry::Between(prior, r.pose);
  if (usable && (moved.Translation().norm() > 0.01 || std::abs(moved.theta) > 0.005)) {
    const double corrected = ExplainedShare(r.pose);
    *refused = corrected < share - options_.min_share_drop;
    if (!*refused) share = corrected;
  }
  if (*refused) ++stats_.corrections_refused;
  return share;
}

void PoseTracker::JudgeLost(const LocalisationResult& r, const Eigen::Matrix3d& covariance,
                            ScanOutcome& out) {
  const double sigma_xy =
      std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance.topLeftCorner<2, 2>())
                    .eigenvalues()
                    .maxCoeff());
  const bool contradicted = r.lost_reason == LostReason::kCorrectionTooLarge ||
                            r.lost_reason == LostReason::kSolverFailed;
  if (!out.lost && out.pinned_directions == 0 && !out.reacquired &&
      (contradicted || sigma_xy > options_.lost_sigma_m)) {
    out.lost = true;
    out.lost_reason = contradicted
                          ? ToString(r.lost_reason)
                          : "position uncertainty beyond lost_sigma_m without a usable scan";
  }
  if (out.lost) ++stats_.scans_lost;
}

PoseTracker::ScanOutcome PoseTracker::ProcessScan(const ScanInput& scan, double waited_s) {
  if (const auto problem = ScanProblem(scan)) return Reject(*problem);
  const double last_beam = scan.stamp + scan.time_increment * static_cast<double>(scan.count - 1);
  const double uncovered = last_beam - history_.Newest();
  if (uncovered > options_.max_extrapolation_s && waited_s < options_.odometry_wait_s) {
    ScanOutcome wait;
    wait.verdict = ScanVerdict::kWaitForOdometry;
    return wait;
  }
  // Odometry must reach the scan's own time (or nearly): a prior from stale
  // odometry would corrupt the map -> odom correction.
  if (scan.stamp < history_.Oldest() ||
      scan.stamp > history_.Newest() + options_.max_extrapolation_s) {
    return Reject(Rejection::kNoOdometry);
  }
  // Odometry at the scan stamp: interpolated, or the newest when it is late.
  const geometry::Pose2D odom =
      *history_.AtOrExtrapolated(scan.stamp, options_.max_extrapolation_s);
  const bool covered = uncovered <= options_.max_extrapolation_s;
  const bool deskew =
      options_.deskew && scan.time_increment > 0 && covered &&
      BeamMotionFromHistory(history_, localiser_.Options().sensor_mount, scan.stamp,
                            scan.time_increment, scan.count, motion_, options_.max_extrapolation_s);
  if (options_.deskew && scan.time_increment > 0 && !deskew) ++stats_.scans_not_deskewed;
  last_scan_stamp_ = scan.stamp;

  // The prior: the filter carried forward by the (calibrated) odometry step.
  filter_.Predict(geometry::Between(odom_at_last_update_, odom));
  odom_at_last_update_ = odom;
  const UpdateInput in = PriorInput(scan, deskew);
  const LocalisationResult& r = localiser_.Update(in);
  ScanOutcome out;
  if (r.rejection != nullptr) {
    // The localiser refused its input: nothing was measured, the prediction stays.
    map_to_odom_ = geometry::Compose(filter_.Pose(), geometry::Inverse(odom));
    return Reject(Rejection::kLocaliserRejected, r.rejection);
  }
  ++stats_.scans_processed;
  bool refused = false;
  double share = -1.0;
  const auto check_start = std::chrono::steady_clock::now();
  if (search_ != nullptr) share = CheckCorrection(scan, in.odometry_pose, r, &refused);
  out.check_us = MicrosecondsSince(check_start);
  out.pinned_directions = refused ? 0 : Correct(r, in, odom);
  map_to_odom_ = geometry::Compose(filter_.Pose(), geometry::Inverse(odom));
  if (search_ != nullptr) {
    out.explained_share = share;  // at the prior or the localiser's correction of it
    const auto search_start = std::chrono::steady_clock::now();
    Reacquire(scan, out);
    out.search_us = MicrosecondsSince(search_start);
  }
  const Eigen::Matrix3d covariance = filter_.PoseCovariance();
  JudgeLost(r, covariance, out);
  out.verdict = ScanVerdict::kProcessed;
  out.result = &r;
  out.pose = {scan.stamp, filter_.Pose(), covariance};
  return out;
}

void PoseTracker::CollectCheckPoints(const ScanInput& scan) {
  check_points_.clear();
  check_verdicts_.clear();
  const auto& o = search_->Options();
  const double lo = std::max(o.min_range_m, scan.range_min);
  const double hi = std::min(o.max_range_m, scan.range_max > 0 ? scan.range_max : o.max_range_m);
  // As many points as the search's refinement uses: the check runs on every scan.
  const size_t step = std::max<size_t>(1, scan.count / static_cast<size_t>(o.max_points));
  // The beams' directions, computed again only when the scan's geometry changes.
  if (scan.count != check_geometry_.count || scan.angle_min != check_geometry_.angle_min ||
      scan.angle_increment != check_geometry_.angle_increment) {
    check_geometry_ = {scan.count, scan.angle_min, scan.angle_increment};
    check_directions_.clear();
    for (size_t i = 0; i < scan.count; i += step) {
      const double a = scan.angle_min + scan.angle_increment * static_cast<double>(i);
      check_directions_.emplace_back(std::cos(a), std::sin(a));
    }
  }
  for (size_t i = 0, k = 0; i < scan.count; i += step, ++k) {
    const double range = scan.ranges[i];
    if (!std::isfinite(range) || range < lo || range >= hi) continue;
    check_points_.push_back(range * check_directions_[k]);
  }
}

double PoseTracker::ExplainedShare(const geometry::Pose2D& pose) {
  return search_->ExplainedShare(
      check_points_, geometry::Compose(pose, localiser_.Options().sensor_mount), check_verdicts_);
}

void PoseTracker::Reacquire(const ScanInput& scan, ScanOutcome& out) {
  const auto& o = search_->Options();
  if (out.explained_share >= options_.min_explained_share ||
      check_points_.size() < static_cast<size_t>(o.min_points)) {
    low_share_since_ = -1.0;
    pending_correction_.reset();
    search_task_.reset();  // explained again: nothing to find
    return;
  }
  if (low_share_since_ < 0.0) low_share_since_ = scan.stamp;
  if (!search_task_) {
    if (scan.stamp - low_share_since_ < options_.reacquire_after_s) return;
    // Lost: search around the tracked pose, as far as its uncertainty says.
    const Eigen::Matrix3d p = filter_.PoseCovariance();
    // The position's largest standard deviation, along its principal axis.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> position(p.topLeftCorner<2, 2>());
    const double sigma_xy = std::sqrt(std::max(0.0, position.eigenvalues().maxCoeff()));
    SearchWindow window;
    window.centre = geometry::Compose(filter_.Pose(), localiser_.Options().sensor_mount);
    // At least 0.5 m, at most reacquire_max_radius_m (even when that is smaller).
    window.radius_m =
        std::min(std::max(3.0 * sigma_xy + 0.5, 0.5), options_.reacquire_max_radius_m);
    window.heading_rad = std::clamp(3.0 * std::sqrt(p(2, 2)) + 0.2, 0.2, geometry::kPi);
    search_points_ = check_points_;
    search_odometry_ = odom_at_last_update_;
    search_share_ = out.explained_share;
    search_stamp_ = scan.stamp;
    search_task_.emplace(*search_, OneScan(search_points_), window);
    return;  // searched between scans, a slice at a time (Anticipate)
  }
  if (!search_task_->Done()) return;
  const GlobalResult found = search_task_->Result();
  search_task_.reset();
  // The next search reacquire_after_s after this one started (at once when
  // this one took longer): searches start no more often than that, and each
  // searches a scan taken further along.
  low_share_since_ = search_stamp_;
  ApplySearch(found, out);
}

void PoseTracker::ApplySearch(const GlobalResult& found, ScanOutcome& out) {
  // A jump must be worth it: the found pose explains at least min_explained_share
  // more of the scan than the tracked one (an unmapped room explains little
  // anywhere; coasting on odometry through it beats jumping to a chance fit).
  // Nothing nearby explains the scan better: a part of the building the map
  // lacks (or changed), not evidence of being lost; the tracker coasts and
  // its uncertainty decides (lost_sigma_m).
  if (found.decision != GlobalDecision::kFound ||
      found.best->score < search_share_ + options_.min_explained_share) {
    pending_correction_.reset();
    return;
  }
  const geometry::Pose2D mount = localiser_.Options().sensor_mount;
  // The robot where the searched scan was taken, and so the map -> odom
  // correction (which odometry carries to the newest scan).
  const geometry::Pose2D searched = geometry::Compose(found.best->pose, geometry::Inverse(mount));
  const geometry::Pose2D correction =
      geometry::Compose(searched, geometry::Inverse(search_odometry_));
  // And it must be found twice: the next search, after more driving, must
  // arrive at the same map -> odom correction. A chance fit (a stretch of
  // corridor the map has fewer walls of, a room like the one the robot is in)
  // moves with the robot; where the robot really is does not.
  const bool confirmed =
      pending_correction_ &&
      (correction.Translation() - pending_correction_->Translation()).norm() <= kSameCorrectionM &&
      std::abs(geometry::WrapAngle(correction.theta - pending_correction_->theta)) <=
          kSameCorrectionRad;
  if (!confirmed) {
    pending_correction_ = correction;
    return;
  }
  pending_correction_.reset();
  const geometry::Pose2D pose = geometry::Compose(correction, odom_at_last_update_);
  const geometry::Pose2D before = filter_.Pose();
  out.jump = {pose.x - before.x, pose.y - before.y, geometry::WrapAngle(pose.theta - before.theta)};
  filter_.Reset(pose, options_.InitialCovariance());
  map_to_odom_ = correction;
  out.reacquired = true;
  out.explained_share = found.best->score;
  low_share_since_ = -1.0;
  ++stats_.reacquisitions;
}

int PoseTracker::Correct(const LocalisationResult& r, const UpdateInput& in,
                         const geometry::Pose2D& odom) {
  // Underdetermined scans still pin some directions; the filter keeps those.
  if (r.lost && r.lost_reason != LostReason::kUnderdetermined) return 0;
  if (corrected_) {
    const geometry::Pose2D moved = geometry::Between(odom_at_last_correction_, odom);
    if (moved.Translation().norm() < options_.min_update_travel_m &&
        std::abs(moved.theta) < options_.min_update_turn_rad) {
      return 0;
    }
  }
  // The solve about the prior gives the posterior r.pose; in information form
  // its gradient is (P^-1 + I)(posterior - prior) = I (z - prior).
  const Eigen::Vector3d delta(r.pose.x - in.odometry_pose.x, r.pose.y - in.odometry_pose.y,
                              geometry::WrapAngle(r.pose.theta - in.odometry_pose.theta));
  const Eigen::Matrix3d prior_information =
      in.odometry_covariance.ldlt().solve(Eigen::Matrix3d::Identity());
  const Eigen::Vector3d gradient = (prior_information + r.information) * delta;
  const int used = filter_.Update(r.information / r.chi2_scale, gradient / r.chi2_scale);
  if (used > 0) {
    localiser_.RememberFused();
    corrected_ = true;
    odom_at_last_correction_ = odom;
  }
  return used;
}

}  // namespace structloc::localisation_core
