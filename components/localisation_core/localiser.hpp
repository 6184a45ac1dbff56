// One position update (thesis 3.4-3.6 and 6.5): scan + odometric pose in, corrected
// pose with covariance, matches, quality and a lost verdict out. Owns every
// buffer it needs, sized at construction, so that the steady-state update
// with the default (expectation) strategy never allocates. DDS-free.
#pragma once

#include <Eigen/Core>
#include <random>
#include <vector>

#include "deskew.hpp"
#include "expected_features.hpp"
#include "localiser_options.hpp"
#include "ray_cast.hpp"
#include "visibility.hpp"
#include "world_model.hpp"

namespace structloc::localisation {

struct UpdateInput {
  ScanView scan;
  geometry::Pose2D odometry_pose;  // robot base in the map frame at the scan stamp
  Eigen::Matrix3d odometry_covariance = Eigen::Matrix3d::Identity();  // of that prediction
  const BeamMotion* motion = nullptr;  // per-beam sensor motion for de-skewing, or none
};

enum class LostReason {
  kNone,
  kRejectedInput,       // the scan or prior was unusable; nothing was computed
  kNoFeatures,          // no expected feature was found in the scan
  kUnderdetermined,     // the features leave a direction of the pose open
  kCorrectionTooLarge,  // the fit would move the robot beyond the gates
  kSolverFailed,
};
const char* ToString(LostReason reason);

struct FeatureMatch {
  int model_id = 0;
  int members = 0;
  double a = 0.0;  // walls: r (m); points: x (m), sensor frame
  double b = 0.0;  // walls: alpha (rad); points: y (m)
  double residual_m = 0.0;
  bool used = false;  // taken into the pose solve
};

struct StepTimes {
  double prefilter_us = 0, line_fit_us = 0, wall_clustering_us = 0, corners_us = 0,
         cylinders_us = 0, solve_us = 0, total_us = 0;
};

struct LocalisationResult {
  const char* rejection = nullptr;  // why the input was rejected, or nullptr
  geometry::Pose2D pose;            // robot base, map frame (odometry when lost)
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  // x, y, theta
  bool lost = false;
  LostReason lost_reason = LostReason::kNone;
  Eigen::Vector3d weak_direction = Eigen::Vector3d::Zero();  // least determined (x, y, theta)
  double quality = 0.0;                                      // 0 .. 1, see Localiser::Update
  int expected_walls = 0, matched_walls = 0;
  int expected_corners = 0, matched_corners = 0;
  int expected_cylinders = 0, matched_cylinders = 0;
  std::vector<FeatureMatch> walls, corners, cylinders;
  PrefilterStats prefilter;
  StepTimes times;
  double chi2 = 0.0;
  int dof = 0;
};

class Localiser {
 public:
  // Throws std::invalid_argument when the options are invalid.
  Localiser(const world::WorldModel& world, const LocaliserOptions& options);

  // Quality = matched / expected features, reduced when chi2/dof exceeds 2;
  // 0 when lost. The returned reference stays valid until the next Update.
  const LocalisationResult& Update(const UpdateInput& input);

  const LocaliserOptions& Options() const { return options_; }
  const world::WorldModel& World() const { return world_; }

 private:
  void RefreshVisibility(const geometry::Pose2D& sensor_pose);
  void Reject(const UpdateInput& input, const char* why);
  void Finish(const UpdateInput& input, const geometry::Pose2D& sensor_prior,
              const Eigen::Matrix3d& sensor_prior_cov);

  const world::WorldModel& world_;
  LocaliserOptions options_;
  world::Scene scene_;
  std::vector<WallLineModel> lines_;
  std::vector<int> wall_line_of_;
  world::Visibility visibility_;
  bool visibility_valid_ = false;
  geometry::Pose2D visibility_pose_;
  std::mt19937 kohonen_rng_;

  BeamDirections directions_;
  ScanPoints points_;
  std::vector<unsigned char> keep_;
  std::vector<WindowLine> windows_;
  ExpectedFeatures expected_;
  std::vector<int> assignment_;
  WallClusterWork wall_work_;
  std::vector<WallCluster> wall_clusters_;
  std::vector<PointSums> corner_work_;
  std::vector<PointCluster> corner_clusters_;
  CylinderWork cylinder_work_;
  std::vector<PointCluster> cylinder_clusters_;
  std::vector<WallMeasurement> wall_measurements_;
  std::vector<PointMeasurement> point_measurements_;
  SolveOutput solve_;
  LocalisationResult result_;
  // Last output, the fallback when an input's own prior is unusable.
  geometry::Pose2D last_pose_;
  Eigen::Matrix3d last_covariance_ = 1e4 * Eigen::Matrix3d::Identity();
};

}  // namespace structloc::localisation
