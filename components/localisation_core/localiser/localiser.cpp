// The whole position update (see header).
#include "structloc/localisation_core/localiser/localiser.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "structloc/localisation_core/expectation/scan_visibility.hpp"
#include "structloc/localisation_core/features/feature_kinds.hpp"

namespace structloc::localisation_core {
namespace {

using Clock = std::chrono::steady_clock;
double Us(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}

// Jacobian of a * m (m fixed) with respect to a, for covariance propagation.
Eigen::Matrix3d ComposeJacobian(const geometry::Pose2D& a, const geometry::Pose2D& m) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  Eigen::Matrix3d j = Eigen::Matrix3d::Identity();
  j(0, 2) = -s * m.x - c * m.y;
  j(1, 2) = c * m.x - s * m.y;
  return j;
}

// Finite, symmetric and positive definite (a Cholesky factor exists: its
// pivots are positive exactly when the eigenvalues are, at a tenth of the
// cost of computing them; this runs three times per update).
bool ValidCovariance(const Eigen::Matrix3d& c) {
  if (!c.allFinite() || (c - c.transpose()).cwiseAbs().maxCoeff() > 1e-9 * (1 + c.norm())) {
    return false;
  }
  return Eigen::LLT<Eigen::Matrix3d>(c).info() == Eigen::Success;
}

}  // namespace

const char* ToString(LostReason reason) {
  switch (reason) {
    case LostReason::kNone:
      return "localised";
    case LostReason::kRejectedInput:
      return "input rejected";
    case LostReason::kNoFeatures:
      return "no expected feature found in the scan";
    case LostReason::kUnderdetermined:
      return "features do not determine the pose in every direction";
    case LostReason::kCorrectionTooLarge:
      return "correction beyond the gates";
    case LostReason::kSolverFailed:
      return "pose solver failed";
  }
  return "unknown";
}

const FeatureKindResult* LocalisationResult::Kind(const char* name) const {
  for (const auto& k : features) {
    if (std::strcmp(k.kind, name) == 0) return &k;
  }
  return nullptr;
}

int LocalisationResult::Expected() const {
  int n = 0;
  for (const auto& k : features) n += k.expected;
  return n;
}

int LocalisationResult::Matched() const {
  int n = 0;
  for (const auto& k : features) n += k.Matched();
  return n;
}

double LocalisationResult::ExtractUs() const {
  double us = 0.0;
  for (const auto& k : features) us += k.extract_us;
  return us;
}

namespace {

// Places whose visibility is kept (VisibilityCache): the robot's surroundings
// for a loop through a few rooms.
constexpr size_t kVisibilityPlaces = 64;

std::vector<std::unique_ptr<FeatureExtractor>> ValidatedExtractors(
    const world_model::WorldModel& world, const LocaliserOptions& options) {
  options.Validate();  // before any buffer is sized by the options
  return MakeFeatureExtractors(options, world, static_cast<size_t>(options.max_beams));
}

}  // namespace

Localiser::Localiser(const world_model::WorldModel& world, const LocaliserOptions& options)
    : Localiser(world, options, ValidatedExtractors(world, options)) {}

Localiser::Localiser(const world_model::WorldModel& world, const LocaliserOptions& options,
                     std::vector<std::unique_ptr<FeatureExtractor>> extractors)
    : world_(world),
      options_(options),
      scene_(world_model::Scene::FromWorld(world)),
      lines_(GroupCollinearWalls(world)),
      visibility_cache_(world, scene_, options.visibility.refresh_distance_m,
                        options.visibility.refresh_angle_rad, kVisibilityPlaces),
      extractors_(std::move(extractors)) {
  options_.Validate();
  wall_line_of_.assign(world.Walls().size(), 0);
  for (size_t l = 0; l < lines_.size(); ++l) {
    for (int w : lines_[l].walls) wall_line_of_[static_cast<size_t>(w)] = static_cast<int>(l);
  }
  const size_t beams = static_cast<size_t>(options_.max_beams);
  directions_.Reserve(beams);
  points_.Reserve(beams);
  windows_.reserve(beams);
  expected_.Reserve(lines_.size(), world.Walls().size());
  // The wall lines take the first slots of the map-error memory, each other
  // kind's features theirs after them.
  size_t slots = lines_.size();
  for (const auto& e : extractors_) {
    if (e == nullptr) throw std::invalid_argument("Localiser: a feature extractor is missing");
    slots += static_cast<size_t>(e->TakeSlots(world, static_cast<int>(slots)));
  }
  const size_t points = slots - lines_.size();  // features measured as points at most
  map_errors_.Reset(slots, options_.map_error_travel_m);
  measurements_.lines.reserve(lines_.size());
  measurements_.points.reserve(points);
  solve_.Reserve(lines_.size(), points);
  for (const auto& e : extractors_) {
    FeatureKindResult k;
    k.kind = e->Kind();
    k.shape = e->Shape();
    k.matches.reserve(std::max(lines_.size(), points));
    result_.features.push_back(std::move(k));
  }
}

void Localiser::Anticipate(const geometry::Pose2D& robot_pose) {
  if (!visibility_cache_.View() || !geometry::IsFinite(robot_pose)) return;
  // Where the next scan will be taken if the robot moves on as it did since
  // the last call (a robot turning half a radian between scans would
  // otherwise always find the visibility computed for the last one stale).
  const geometry::Pose2D sensor = geometry::Compose(robot_pose, options_.sensor_mount);
  geometry::Pose2D next = sensor;
  if (last_anticipated_) {
    next.x += sensor.x - last_anticipated_->x;
    next.y += sensor.y - last_anticipated_->y;
    next.theta = geometry::WrapAngle(sensor.theta +
                                     geometry::WrapAngle(sensor.theta - last_anticipated_->theta));
  }
  last_anticipated_ = sensor;
  if (visibility_cache_.Find(next) < 0) visibility_cache_.Compute(next, visibility_entry_);
}

void Localiser::RefreshVisibility(const geometry::Pose2D& sensor_pose, const ScanView& scan) {
  if (visibility_cache_.SetView(ScanVisibility(options_, scan))) visibility_entry_ = -1;
  if (visibility_entry_ >= 0 && visibility_cache_.Holds(visibility_entry_, sensor_pose)) return;
  int entry = visibility_cache_.Find(sensor_pose);
  // Nothing to fall back on (the first scan, or a new view): computed here.
  if (entry < 0 && visibility_entry_ < 0) entry = visibility_cache_.Compute(sensor_pose);
  if (entry < 0) {
    // None holds: the newest computed, for the pose nearest this scan's.
    entry = visibility_cache_.Newest();
    ++stale_visibility_updates_;
  }
  visibility_entry_ = entry;
}

void Localiser::ApplyMapErrorMemory(const geometry::Pose2D& sensor_pose) {
  if (!map_errors_.Enabled()) return;
  if (map_errors_pose_)
    map_errors_.Travel((sensor_pose.Translation() - map_errors_pose_->Translation()).norm());
  map_errors_pose_ = sensor_pose;
  for (auto& w : expected_.walls) w.map_error_scale = map_errors_.MapErrorScale(w.slot);
}

void Localiser::RememberFused() {
  for (const auto& kind : result_.features) {
    for (const auto& m : kind.matches) {
      if (m.used) map_errors_.RememberFused(m.slot);
    }
  }
}

void Localiser::Reject(const UpdateInput& input, const char* why) {
  // Field by field, so that the per-kind buffers stay allocated.
  auto features = std::move(result_.features);
  result_ = LocalisationResult{};
  for (auto& k : features) {
    k.expected = 0;
    k.matches.clear();
    k.extract_us = 0.0;
  }
  result_.features = std::move(features);
  result_.rejection = why;
  result_.lost = true;
  result_.lost_reason = LostReason::kRejectedInput;
  // Never hand out a NaN: an unusable prior falls back to the last good pose.
  const bool prior_ok = geometry::IsFinite(input.odometry_pose);
  result_.pose = prior_ok ? input.odometry_pose : last_pose_;
  result_.covariance = prior_ok && ValidCovariance(input.odometry_covariance)
                           ? input.odometry_covariance
                           : last_covariance_;
}

const LocalisationResult& Localiser::Update(const UpdateInput& input) {
  const auto t0 = Clock::now();
  const auto& scan = input.scan;
  if (scan.count == 0 || scan.ranges == nullptr) {
    Reject(input, "empty scan");
    return result_;
  }
  if (scan.count > static_cast<size_t>(options_.max_beams)) {
    Reject(input, "more beams than max_beams");
    return result_;
  }
  if (!std::isfinite(scan.angle_min) || !std::isfinite(scan.angle_increment) ||
      scan.angle_increment == 0.0 ||
      std::abs(scan.angle_increment) * static_cast<double>(scan.count) > 2 * geometry::kPi + 1e-3) {
    Reject(input, "invalid scan angles (angle_increment 0, non-finite, or over 360 degrees)");
    return result_;
  }
  if (!geometry::IsFinite(input.odometry_pose) || !ValidCovariance(input.odometry_covariance)) {
    Reject(input, "odometry pose or covariance not finite / not positive definite");
    return result_;
  }
  if (input.motion != nullptr && input.motion->Size() != scan.count) {
    Reject(input, "beam motion does not match the beam count");
    return result_;
  }
  result_.rejection = nullptr;
  result_.prefilter = PrefilterStats{};
  const geometry::Pose2D sensor_prior =
      geometry::Compose(input.odometry_pose, options_.sensor_mount);
  const Eigen::Matrix3d jm = ComposeJacobian(input.odometry_pose, options_.sensor_mount);
  const Eigen::Matrix3d sensor_prior_cov = jm * input.odometry_covariance * jm.transpose();

  RefreshVisibility(sensor_prior, scan);
  const auto& visibility = visibility_cache_.At(visibility_entry_);
  ComputeExpectedWalls(world_, lines_, wall_line_of_, visibility, sensor_prior, expected_);
  ApplyMapErrorMemory(sensor_prior);
  const ExpectationInput expectation{&world_, &visibility, &expected_, sensor_prior, &map_errors_};
  for (auto& e : extractors_) e->Expect(expectation);
  const auto t_expected = Clock::now();

  // 1. Prefilter (+ de-skew before the neighbourhood tests).
  directions_.Update(scan);
  Prefilter(scan, directions_, options_.prefilter, input.motion, points_, result_.prefilter);
  const auto t1 = Clock::now();
  // 2. Sliding line fits.
  FitWindowLines(points_, options_.line_fit, windows_);
  const auto t2 = Clock::now();
  // 3. The feature kinds (walls, corners, cylinders, ...), each timed.
  ExtractFeatures(sensor_prior, sensor_prior_cov);
  const auto t3 = Clock::now();
  // 4. Pose.
  geometry::Pose2D sensor_pose = sensor_prior;
  Eigen::Matrix3d sensor_cov = sensor_prior_cov;
  SolveAndGate(sensor_prior, sensor_prior_cov, sensor_pose, sensor_cov);
  PackMatches();
  FinishResult(input, sensor_pose, sensor_cov);
  const auto t4 = Clock::now();
  last_pose_ = result_.pose;
  last_covariance_ = result_.covariance;
  auto& times = result_.times;
  times.expectation_us = Us(t0, t_expected);
  times.prefilter_us = Us(t_expected, t1);
  times.line_fit_us = Us(t1, t2);
  times.solve_us = Us(t3, t4);
  times.total_us = Us(t0, t4);
  return result_;
}

void Localiser::ExtractFeatures(const geometry::Pose2D& sensor_prior,
                                const Eigen::Matrix3d& sensor_prior_cov) {
  ExtractionInput in;
  in.sensor_prior_covariance = sensor_prior_cov;
  in.expected = &expected_;
  in.windows = &windows_;
  in.points = &points_;
  in.sensor_prior = sensor_prior;
  in.window_points = options_.line_fit.window_points;
  in.thesis_values = options_.solver.mode != SolverMode::kWeighted;
  measurements_.Clear();
  auto start = Clock::now();  // one kind's end is the next one's start
  for (size_t i = 0; i < extractors_.size(); ++i) {
    auto& kind = result_.features[i];
    kind.matches.clear();
    kind.expected = extractors_[i]->Expected();
    extractors_[i]->Extract(in, measurements_, kind.matches);
    const auto end = Clock::now();
    kind.extract_us = Us(start, end);
    start = end;
  }
}

void Localiser::SolveAndGate(const geometry::Pose2D& sensor_prior,
                             const Eigen::Matrix3d& sensor_prior_cov, geometry::Pose2D& sensor_pose,
                             Eigen::Matrix3d& sensor_cov) {
  auto& r = result_;
  r.weak_direction.setZero();
  r.lost = false;
  r.lost_reason = LostReason::kNone;
  if (measurements_.lines.empty() && measurements_.points.empty()) {
    r.lost = true;
    r.lost_reason = LostReason::kNoFeatures;
    return;
  }
  SolveInput in;
  in.walls = &measurements_.lines;
  in.points = &measurements_.points;
  in.prior = sensor_prior;
  in.prior_covariance = sensor_prior_cov;
  Solve(in, options_.solver, solve_);
  r.chi2 = solve_.chi2;
  r.dof = solve_.dof;
  const Eigen::Vector3d correction(solve_.pose.x - sensor_prior.x, solve_.pose.y - sensor_prior.y,
                                   geometry::WrapAngle(solve_.pose.theta - sensor_prior.theta));
  // A covariance that is not symmetric positive definite (e.g. inflated by
  // chi2 / dof over many underdetermined scans) would make every later prior
  // unusable: the fit failed.
  if (!geometry::IsFinite(solve_.pose) || !ValidCovariance(solve_.covariance)) {
    r.lost = true;
    r.lost_reason = LostReason::kSolverFailed;
  } else if (correction.head<2>().norm() > options_.max_correction_m ||
             std::abs(correction.z()) > options_.max_correction_rad) {
    r.lost = true;
    r.lost_reason = LostReason::kCorrectionTooLarge;
  } else {
    sensor_pose = solve_.pose;
    sensor_cov = solve_.covariance;
    CheckObservability();
  }
}

void Localiser::CheckObservability() {
  // From the features alone: each eigen-direction of their information must be
  // pinned to within the configured standard deviation.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(solve_.feature_information);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d v = eig.eigenvectors().col(k);
    const double limit = v.head<2>().norm() * options_.solver.max_feature_std_m +
                         std::abs(v.z()) * options_.solver.max_feature_std_rad;
    const double lambda = eig.eigenvalues()(k);
    if (!(lambda > 0.0) || 1.0 / std::sqrt(lambda) > limit) {
      result_.lost = true;
      result_.lost_reason = LostReason::kUnderdetermined;
      result_.weak_direction = v;
      return;
    }
  }
}

void Localiser::PackMatches() {
  if (result_.lost_reason == LostReason::kNoFeatures) return;
  for (auto& kind : result_.features) {
    const bool line = kind.shape == FeatureShape::kLine;
    for (auto& m : kind.matches) {
      const auto row = static_cast<size_t>(m.row);
      m.residual_m = line ? solve_.wall_residual[row] : solve_.point_residual[row];
      m.used = (line ? solve_.wall_used[row] : solve_.point_used[row]) != 0;
    }
  }
}

void Localiser::FinishResult(const UpdateInput& input, const geometry::Pose2D& sensor_pose,
                             const Eigen::Matrix3d& sensor_cov) {
  auto& r = result_;
  // Back from the sensor to the robot base.
  const geometry::Pose2D unmount = geometry::Inverse(options_.sensor_mount);
  r.pose = geometry::Compose(sensor_pose, unmount);
  const Eigen::Matrix3d ju = ComposeJacobian(sensor_pose, unmount);
  r.covariance = ju * sensor_cov * ju.transpose();
  r.covariance = 0.5 * (r.covariance + r.covariance.transpose());  // exact, despite rounding
  r.information.setZero();
  r.chi2_scale = r.dof > 0 ? std::max(1.0, r.chi2 / r.dof) : 1.0;
  if (!r.lost || r.lost_reason == LostReason::kUnderdetermined) {
    const Eigen::Matrix3d ju_inv = ju.inverse();
    r.information = ju_inv.transpose() * solve_.feature_information * ju_inv;
    r.information = 0.5 * (r.information + r.information.transpose());
  }
  if (r.lost_reason == LostReason::kCorrectionTooLarge ||
      r.lost_reason == LostReason::kSolverFailed) {
    r.pose = input.odometry_pose;
    r.covariance = input.odometry_covariance;
  }
  const int expected = r.Expected();
  double q = expected > 0 ? std::min(1.0, static_cast<double>(r.Matched()) / expected) : 0.0;
  const double chi2_limit = options_.solver.quality_chi2_per_dof;
  if (r.dof > 0 && r.chi2 / r.dof > chi2_limit) q *= chi2_limit / (r.chi2 / r.dof);
  r.quality = r.lost ? 0.0 : q;
}

}  // namespace structloc::localisation_core
