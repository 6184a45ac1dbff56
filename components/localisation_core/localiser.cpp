// The whole position update (see header).
#include "localiser.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <optional>

namespace structloc::localisation {
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

bool ValidCovariance(const Eigen::Matrix3d& c) {
  if (!c.allFinite() || (c - c.transpose()).cwiseAbs().maxCoeff() > 1e-9 * (1 + c.norm())) {
    return false;
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c, Eigen::EigenvaluesOnly)
             .eigenvalues()
             .minCoeff() > 0.0;
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

Localiser::Localiser(const world::WorldModel& world, const LocaliserOptions& options)
    : world_(world),
      options_(options),
      scene_(world::Scene::FromWorld(world)),
      lines_(GroupCollinearWalls(world)),
      kohonen_rng_(options.kohonen_seed) {
  options_.Validate();
  wall_line_of_.assign(world.Walls().size(), 0);
  for (size_t l = 0; l < lines_.size(); ++l) {
    for (int w : lines_[l].walls) wall_line_of_[static_cast<size_t>(w)] = static_cast<int>(l);
  }
  const size_t beams = static_cast<size_t>(options_.max_beams);
  const size_t nw = world.Walls().size(), nc = world.Corners().size(),
               ny = world.Cylinders().size();
  visibility_.walls.reserve(nw);
  visibility_.corners.reserve(nc);
  visibility_.cylinders.reserve(ny);
  directions_.Reserve(beams);
  points_.Reserve(beams);
  keep_.reserve(beams);
  windows_.reserve(beams);
  expected_.Reserve(lines_.size(), nc, ny);
  assignment_.reserve(beams);
  wall_work_.Reserve(beams, lines_.size());
  wall_clusters_.reserve(lines_.size());
  corner_work_.reserve(nc);
  corner_clusters_.reserve(nc);
  cylinder_work_.Reserve(beams, ny);
  cylinder_clusters_.reserve(ny);
  wall_measurements_.reserve(lines_.size());
  point_measurements_.reserve(nc + ny);
  solve_.Reserve(lines_.size(), nc + ny);
  result_.walls.reserve(lines_.size());
  result_.corners.reserve(nc);
  result_.cylinders.reserve(ny);
}

void Localiser::RefreshVisibility(const geometry::Pose2D& sensor_pose) {
  const auto& v = options_.visibility;
  const bool full_circle = v.field_of_view_rad >= 2 * geometry::kPi - 1e-9;
  if (visibility_valid_ &&
      (sensor_pose.Translation() - visibility_pose_.Translation()).norm() < v.refresh_distance_m &&
      (full_circle || std::abs(geometry::WrapAngle(sensor_pose.theta - visibility_pose_.theta)) <
                          v.refresh_angle_rad)) {
    return;
  }
  world::VisibilityOptions o;
  o.min_range_m = options_.prefilter.min_range_m;
  o.max_range_m = options_.prefilter.max_range_m;
  o.field_of_view_rad = v.field_of_view_rad;
  o.min_visible_length_m = v.min_visible_length_m;
  o.max_incidence_rad = v.max_incidence_rad;
  world::ComputeVisibility(world_, scene_, sensor_pose, o, visibility_);
  visibility_pose_ = sensor_pose;
  visibility_valid_ = true;
}

void Localiser::Reject(const UpdateInput& input, const char* why) {
  result_ = LocalisationResult{};
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

  RefreshVisibility(sensor_prior);
  ComputeExpectedFeatures(world_, lines_, wall_line_of_, visibility_, sensor_prior, expected_);

  // 1. Prefilter (+ de-skew before the neighbourhood tests).
  directions_.Update(scan);
  RangeGate(scan, directions_, options_.prefilter, points_, result_.prefilter);
  if (input.motion != nullptr) Deskew(*input.motion, points_);
  RejectUnsupported(options_.prefilter, points_, keep_, result_.prefilter);
  Thin(options_.prefilter, points_, result_.prefilter);
  const auto t1 = Clock::now();
  // 2. Sliding line fits.
  FitWindowLines(points_, options_.line_fit, windows_);
  const auto t2 = Clock::now();
  // 3. Walls.
  if (options_.wall_strategy == WallStrategy::kKohonen) {
    AssignWindowsByKohonen(windows_, expected_, options_.walls, options_.kohonen, kohonen_rng_,
                           assignment_);
  } else {
    AssignWindowsByExpectation(windows_, expected_, sensor_prior, options_.walls, assignment_);
  }
  BuildWallClusters(windows_, assignment_, points_, options_.line_fit.window_points, expected_,
                    options_.walls, wall_work_, wall_clusters_);
  const auto t3 = Clock::now();
  // 4. Corners.
  corner_clusters_.clear();
  if (options_.use_corners) {
    ExtractCorners(windows_, points_.wraps, expected_, options_.corners,
                   options_.line_fit.window_points, corner_work_, corner_clusters_);
  }
  const auto t4 = Clock::now();
  // 5. Cylinders.
  cylinder_clusters_.clear();
  if (options_.use_cylinders) {
    ExtractCylinders(windows_, points_, expected_, options_.cylinders,
                     options_.line_fit.window_points, cylinder_work_, cylinder_clusters_);
  }
  const auto t5 = Clock::now();
  // 6. Pose.
  Finish(input, sensor_prior, sensor_prior_cov);
  const auto t6 = Clock::now();
  last_pose_ = result_.pose;
  last_covariance_ = result_.covariance;
  auto& times = result_.times;
  times.prefilter_us = Us(t0, t1);
  times.line_fit_us = Us(t1, t2);
  times.wall_clustering_us = Us(t2, t3);
  times.corners_us = Us(t3, t4);
  times.cylinders_us = Us(t4, t5);
  times.solve_us = Us(t5, t6);
  times.total_us = Us(t0, t6);
  return result_;
}

void Localiser::Finish(const UpdateInput& input, const geometry::Pose2D& sensor_prior,
                       const Eigen::Matrix3d& sensor_prior_cov) {
  const bool thesis_values = options_.solver.mode != SolverMode::kWeighted;
  wall_measurements_.clear();
  for (const auto& c : wall_clusters_) {
    const auto& e = expected_.walls[static_cast<size_t>(c.expected_index)];
    WallMeasurement m;
    m.r = thesis_values ? c.mean_r : c.refined_r;
    m.alpha = thesis_values ? c.mean_alpha : c.refined_alpha;
    m.covariance = c.covariance;
    m.world_r = e.world.r;
    m.world_alpha = e.world.alpha;
    wall_measurements_.push_back(m);
  }
  point_measurements_.clear();
  for (const auto& c : corner_clusters_) {
    const auto& e = expected_.corners[static_cast<size_t>(c.expected_index)];
    PointMeasurement m;
    m.sensor = thesis_values ? c.mean : c.refined;
    m.covariance = c.covariance;
    m.world = e.world;
    // A corner where two matched, non-parallel walls meet adds nothing they
    // do not already say; counting it twice would make the covariance lie.
    std::optional<double> first_alpha;  // of the first matched wall through the corner
    bool redundant = false;
    for (const auto& w : wall_measurements_) {
      const bool through_corner =
          std::abs(e.world.x() * std::cos(w.world_alpha) + e.world.y() * std::sin(w.world_alpha) -
                   w.world_r) < 0.05;
      if (!through_corner) continue;
      if (!first_alpha) {
        first_alpha = w.world_alpha;
      } else if (std::abs(std::sin(w.world_alpha - *first_alpha)) > 0.5) {
        redundant = true;
        break;
      }
    }
    m.use_in_weighted = !redundant;
    point_measurements_.push_back(m);
  }
  for (const auto& c : cylinder_clusters_) {
    const auto& e = expected_.cylinders[static_cast<size_t>(c.expected_index)];
    PointMeasurement m;
    m.sensor = thesis_values ? c.mean : c.refined;
    m.covariance = c.covariance;
    m.world = e.world;
    m.cylinder = true;
    point_measurements_.push_back(m);
  }

  auto& r = result_;
  r.expected_walls = static_cast<int>(expected_.walls.size());
  r.expected_corners = static_cast<int>(expected_.corners.size());
  r.expected_cylinders = static_cast<int>(expected_.cylinders.size());
  r.matched_walls = static_cast<int>(wall_clusters_.size());
  r.matched_corners = static_cast<int>(corner_clusters_.size());
  r.matched_cylinders = static_cast<int>(cylinder_clusters_.size());
  r.walls.clear();
  r.corners.clear();
  r.cylinders.clear();
  r.weak_direction.setZero();
  r.lost = false;
  r.lost_reason = LostReason::kNone;

  SolveInput in;
  in.walls = &wall_measurements_;
  in.points = &point_measurements_;
  in.prior = sensor_prior;
  in.prior_covariance = sensor_prior_cov;
  geometry::Pose2D sensor_pose = sensor_prior;
  Eigen::Matrix3d sensor_cov = sensor_prior_cov;
  const size_t features = wall_measurements_.size() + point_measurements_.size();
  if (features == 0) {
    r.lost = true;
    r.lost_reason = LostReason::kNoFeatures;
  } else {
    Solve(in, options_.solver, solve_);
    r.chi2 = solve_.chi2;
    r.dof = solve_.dof;
    const Eigen::Vector3d correction(solve_.pose.x - sensor_prior.x, solve_.pose.y - sensor_prior.y,
                                     geometry::WrapAngle(solve_.pose.theta - sensor_prior.theta));
    if (!geometry::IsFinite(solve_.pose) || !solve_.covariance.allFinite()) {
      r.lost = true;
      r.lost_reason = LostReason::kSolverFailed;
    } else if (correction.head<2>().norm() > options_.max_correction_m ||
               std::abs(correction.z()) > options_.max_correction_rad) {
      r.lost = true;
      r.lost_reason = LostReason::kCorrectionTooLarge;
    } else {
      sensor_pose = solve_.pose;
      sensor_cov = solve_.covariance;
      // Observability from the features alone: each eigen-direction of their
      // information must be pinned to within the configured standard deviation.
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(solve_.feature_information);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d v = eig.eigenvectors().col(k);
        const double limit = v.head<2>().norm() * options_.solver.max_feature_std_m +
                             std::abs(v.z()) * options_.solver.max_feature_std_rad;
        const double lambda = eig.eigenvalues()(k);
        if (!(lambda > 0.0) || 1.0 / std::sqrt(lambda) > limit) {
          r.lost = true;
          r.lost_reason = LostReason::kUnderdetermined;
          r.weak_direction = v;
          break;
        }
      }
    }
    for (size_t i = 0; i < wall_clusters_.size(); ++i) {
      const auto& c = wall_clusters_[i];
      r.walls.push_back({expected_.walls[static_cast<size_t>(c.expected_index)].model_id, c.members,
                         wall_measurements_[i].r, wall_measurements_[i].alpha,
                         solve_.wall_residual[i], solve_.wall_used[i] != 0});
    }
    for (size_t i = 0; i < point_measurements_.size(); ++i) {
      const bool corner = i < corner_clusters_.size();
      const auto& c =
          corner ? corner_clusters_[i] : cylinder_clusters_[i - corner_clusters_.size()];
      const auto& e = corner ? expected_.corners[static_cast<size_t>(c.expected_index)]
                             : expected_.cylinders[static_cast<size_t>(c.expected_index)];
      (corner ? r.corners : r.cylinders)
          .push_back({e.model_id, c.members, point_measurements_[i].sensor.x(),
                      point_measurements_[i].sensor.y(), solve_.point_residual[i],
                      solve_.point_used[i] != 0});
    }
  }
  // Back from the sensor to the robot base.
  const geometry::Pose2D unmount = geometry::Inverse(options_.sensor_mount);
  r.pose = geometry::Compose(sensor_pose, unmount);
  const Eigen::Matrix3d ju = ComposeJacobian(sensor_pose, unmount);
  r.covariance = ju * sensor_cov * ju.transpose();
  if (r.lost_reason == LostReason::kCorrectionTooLarge ||
      r.lost_reason == LostReason::kSolverFailed) {
    r.pose = input.odometry_pose;
    r.covariance = input.odometry_covariance;
  }
  const int expected = r.expected_walls + r.expected_corners + r.expected_cylinders;
  const int matched = r.matched_walls + r.matched_corners + r.matched_cylinders;
  double q = expected > 0 ? std::min(1.0, static_cast<double>(matched) / expected) : 0.0;
  if (r.dof > 0 && r.chi2 / r.dof > 2.0) q *= 2.0 / (r.chi2 / r.dof);
  r.quality = r.lost ? 0.0 : q;
}

}  // namespace structloc::localisation
