// Step 6 (thesis 3.5.1, 3.5.4, 3.5.6, 3.5.8): the sensor pose from matched walls, corners,
// cylinders and the odometric prior. Three solvers:
//   kWeighted  (default, beyond the thesis) one weighted nonlinear least-squares
//              problem in (x, y, theta) jointly, Gauss-Newton, every row weighted
//              by its measured covariance and the prior by the odometry's;
//              outliers beyond a chi-square gate are dropped and the fit redone.
//   kThesisLinear  theta = circular mean of alpha_W - alpha_R, then the linear
//              system of EQ 11/12/30 by SVD, equal weights, odometry rows only
//              when the walls leave a direction unconstrained.
//   kBisection (thesis 3.5.8) minimise S_tot (EQ 41-44) by bisection on its
//              partial derivatives inside odometry +- search_half_width_m.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::localisation_core {

enum class SolverMode { kWeighted, kThesisLinear, kBisection };

struct SolverOptions {
  SolverMode mode = SolverMode::kWeighted;
  int max_iterations = 10;           // Gauss-Newton iterations
  double outlier_chi2 = 13.8;        // 2-dof chi-square gate (99.9 %) for a feature
  double search_half_width_m = 0.2;  // bisection window around odometry (thesis)
  int bisection_iterations = 10;     // per coordinate and sweep (thesis example: 10)
  double max_feature_std_m = 0.05;   // features alone must pin every direction this well
  double max_feature_std_rad = 0.05;
  // Quality = matched / expected features, scaled down by quality_chi2_per_dof /
  // (chi2 / dof) when the fit's chi2 per degree of freedom exceeds this.
  double quality_chi2_per_dof = 2.0;
};

// A matched wall in the sensor frame, oriented like its world line's normal.
struct WallMeasurement {
  double r = 0, alpha = 0;  // measured
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  double world_r = 0, world_alpha = 0;
};

// How the thesis' bisection solver pulls the position towards a matched point:
// to where the point's position puts the sensor (EQ 41, a corner), or only to
// its measured distance from the point (EQ 43, a pillar's centre: the circle
// of that radius around it).
enum class BisectionTerm { kPosition, kDistance };

// A matched point feature (a corner, a pillar's centre, ...) in the sensor frame.
struct PointMeasurement {
  Eigen::Vector2d sensor{0, 0};
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  Eigen::Vector2d world{0, 0};
  BisectionTerm bisection = BisectionTerm::kPosition;
  bool use_in_weighted = true;  // false when redundant with two matched walls
};

struct SolveInput {
  const std::vector<WallMeasurement>* walls = nullptr;
  const std::vector<PointMeasurement>* points = nullptr;
  geometry::Pose2D prior;  // odometric sensor pose
  Eigen::Matrix3d prior_covariance = Eigen::Matrix3d::Identity();
};

struct SolveOutput {
  geometry::Pose2D pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  // Information from the features alone (no prior), to judge observability.
  Eigen::Matrix3d feature_information = Eigen::Matrix3d::Zero();
  double chi2 = 0.0;
  int dof = 0;
  int iterations = 0;
  bool converged = false;
  // Per measurement: residual norm (m) and whether it was used.
  std::vector<double> wall_residual;
  std::vector<unsigned char> wall_used;
  std::vector<double> point_residual;
  std::vector<unsigned char> point_used;
  // Scratch of the weighted solver, the same for every iteration: each wall's
  // cos/sin of its world angle, each measurement's information (inverse covariance).
  std::vector<Eigen::Vector2d> wall_direction;
  std::vector<Eigen::Matrix2d> wall_information;
  std::vector<Eigen::Matrix2d> point_information;
  void Reserve(size_t walls, size_t points);
};

void SolveWeighted(const SolveInput& input, const SolverOptions& options, SolveOutput& out);
void SolveThesisLinear(const SolveInput& input, const SolverOptions& options, SolveOutput& out);
void SolveBisection(const SolveInput& input, const SolverOptions& options, SolveOutput& out);
void Solve(const SolveInput& input, const SolverOptions& options, SolveOutput& out);

}  // namespace structloc::localisation_core
