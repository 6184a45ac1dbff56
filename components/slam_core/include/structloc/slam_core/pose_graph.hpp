// The SLAM back end: a graph of robot poses tied by measured relative poses
// (consecutive scans matched, loops closed), optimised by Ceres Solver. A
// loop closure that is wrong must not bend the building: edges marked robust
// go through a Cauchy loss, so one whose error stays large after the others
// agree is weighed down rather than obeyed. The first pose is held fixed (the
// map frame). DDS-free.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::slam_core {

// Pose `to` as measured in the frame of pose `from`, with the information
// (inverse covariance) of that measurement (x, y in metres, theta in radians).
struct PoseGraphEdge {
  int from = 0;
  int to = 0;
  geometry::Pose2D measured;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  bool robust = false;  // a loop closure: through the Cauchy loss
};

struct PoseGraphOptions {
  // The Cauchy loss's scale, in standard deviations of the edge's own
  // covariance: an edge this far off counts half as much as a quadratic one.
  double robust_scale_sigmas = 3.0;
  int max_iterations = 100;
};

struct PoseGraphSummary {
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  bool usable = false;  // Ceres ended with a usable solution
};

// Optimises `poses` (the initial guess on entry) under `edges`; throws
// std::invalid_argument for an edge naming a pose that does not exist or an
// information matrix that is not finite.
PoseGraphSummary OptimisePoseGraph(std::vector<geometry::Pose2D>& poses,
                                   const std::vector<PoseGraphEdge>& edges,
                                   const PoseGraphOptions& options = {});

// The weighted error of one edge under `poses` (its Mahalanobis distance).
double EdgeError(const std::vector<geometry::Pose2D>& poses, const PoseGraphEdge& edge);

}  // namespace structloc::slam_core
