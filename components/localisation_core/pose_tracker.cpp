// Pose tracking around the Localiser (see header).
#include "structloc/localisation_core/pose_tracker.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

namespace structloc::localisation_core {

Eigen::Matrix3d UsableCovariance(const Eigen::Matrix3d& solved, const Eigen::Matrix3d& prior) {
  const Eigen::Matrix3d symmetric = 0.5 * (solved + solved.transpose());
  if (!symmetric.allFinite() || Eigen::LLT<Eigen::Matrix3d>(symmetric).info() != Eigen::Success)
    return prior;
  return symmetric;
}

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

uint64_t TrackerStats::Rejected() const {
  uint64_t n = 0;
  for (auto c : rejected) n += c;
  return n;
}

PoseTracker::PoseTracker(const world_model::WorldModel& world,
                         const LocaliserOptions& localiser_options, const TrackerOptions& options)
    : localiser_(world, localiser_options), options_(options), history_(4096) {
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
  covariance_ = covariance;
  initialised_ = true;
  return std::nullopt;
}

std::optional<TrackedPose> PoseTracker::Latest() const {
  if (!initialised_ || history_.Empty()) return std::nullopt;
  const geometry::Pose2D odom = *history_.At(history_.Newest());
  return TrackedPose{history_.Newest(), geometry::Compose(map_to_odom_, odom), covariance_};
}

PoseTracker::ScanOutcome PoseTracker::ProcessScan(const ScanInput& scan, double waited_s) {
  if (scan.count == 0 || scan.ranges == nullptr) return Reject(Rejection::kEmptyScan);
  if (!std::isfinite(scan.angle_increment) || scan.angle_increment == 0.0 ||
      !std::isfinite(scan.angle_min) || !std::isfinite(scan.stamp) ||
      !std::isfinite(scan.time_increment) || scan.time_increment < 0) {
    return Reject(Rejection::kBadScanGeometry);
  }
  if (scan.time_increment * static_cast<double>(scan.count) > options_.max_scan_duration_s) {
    return Reject(Rejection::kScanTooLong);
  }
  if (scan.count > static_cast<size_t>(localiser_.Options().max_beams)) {
    return Reject(Rejection::kTooManyBeams);
  }
  if (std::isfinite(scan.angle_max)) {
    const double implied = (scan.angle_max - scan.angle_min) / scan.angle_increment + 1.0;
    if (std::abs(implied - static_cast<double>(scan.count)) > 1.01) {
      return Reject(Rejection::kBeamCountMismatch);
    }
  }
  if (!(scan.stamp > last_scan_stamp_)) return Reject(Rejection::kScanOutOfOrder);
  if (history_.Empty()) return Reject(Rejection::kNoOdometry);
  if (scan.stamp > history_.Newest() + options_.max_future_s)
    return Reject(Rejection::kScanInFuture);
  if (!initialised_) return Reject(Rejection::kNoInitialPose);
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

  // The prior: the last correction carried forward, uncertainty grown with the motion.
  const geometry::Pose2D moved = geometry::Between(odom_at_last_update_, odom);
  const double d = moved.Translation().norm();
  const double sxy = options_.odometry_sigma_xy_per_m * d;
  const double st = options_.odometry_sigma_theta_per_m * d +
                    options_.odometry_sigma_theta_per_rad * std::abs(moved.theta);
  UpdateInput in;
  in.scan.ranges = scan.ranges;
  in.scan.count = scan.count;
  in.scan.angle_min = scan.angle_min;
  in.scan.angle_increment = scan.angle_increment;
  in.scan.time_increment = scan.time_increment;
  in.scan.range_min = scan.range_min;
  in.scan.range_max = scan.range_max;
  in.odometry_pose = geometry::Compose(map_to_odom_, odom);
  in.odometry_covariance = covariance_;
  in.odometry_covariance(0, 0) += sxy * sxy + 1e-8;
  in.odometry_covariance(1, 1) += sxy * sxy + 1e-8;
  in.odometry_covariance(2, 2) += st * st + 1e-10;
  in.motion = deskew ? &motion_ : nullptr;
  const LocalisationResult& r = localiser_.Update(in);
  if (r.rejection != nullptr) {
    // The localiser refused its input: nothing was measured, the prior stays.
    covariance_ = in.odometry_covariance;
    odom_at_last_update_ = odom;
    return Reject(Rejection::kLocaliserRejected, r.rejection);
  }
  ++stats_.scans_processed;
  if (r.lost) ++stats_.scans_lost;
  // A lost update leaves the correction alone (dead reckoning continues) but
  // keeps the grown uncertainty; underdetermined updates still correct the
  // determined directions, since the solver held the others at the prior.
  const bool use = !r.lost || r.lost_reason == LostReason::kUnderdetermined;
  if (use) {
    map_to_odom_ = geometry::Compose(r.pose, geometry::Inverse(odom));
    covariance_ = UsableCovariance(r.covariance, in.odometry_covariance);
  } else {
    covariance_ = in.odometry_covariance;
  }
  odom_at_last_update_ = odom;
  ScanOutcome out;
  out.verdict = ScanVerdict::kProcessed;
  out.result = &r;
  out.pose = {scan.stamp, geometry::Compose(map_to_odom_, odom), covariance_};
  return out;
}

}  // namespace structloc::localisation_core
