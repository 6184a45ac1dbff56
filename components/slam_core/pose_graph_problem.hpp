// The pose graph's edges as Ceres residuals, and the solve that holds the
// first pose fixed: shared by the pose-graph optimisation and the
// pose-and-wall refinement, so both weigh an edge the same way. Internal to
// slam_core.
#pragma once

#include <ceres/ceres.h>

#include <array>
#include <vector>

#include "structloc/slam_core/pose_graph.hpp"

namespace structloc::slam_core::internal {

// One Ceres parameter block (x, y, theta) per pose.
using PoseBlocks = std::vector<std::array<double, 3>>;

PoseBlocks ToBlocks(const std::vector<geometry::Pose2D>& poses);
// Writes the blocks back, headings wrapped.
void FromBlocks(const PoseBlocks& blocks, std::vector<geometry::Pose2D>& poses);

// Adds every edge to `problem` (robust ones through the Cauchy loss); throws
// std::invalid_argument for an edge naming a pose that does not exist or an
// information matrix that is not finite and positive definite.
void AddEdges(const std::vector<PoseGraphEdge>& edges, const PoseGraphOptions& options,
              ceres::Problem& problem, PoseBlocks& blocks);

// Solves with the first pose held fixed (the map frame).
ceres::Solver::Summary Solve(const PoseGraphOptions& options, ceres::Problem& problem,
                             PoseBlocks& blocks);

}  // namespace structloc::slam_core::internal
