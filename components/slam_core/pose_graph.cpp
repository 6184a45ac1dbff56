// Pose-graph optimisation with Ceres Solver (see header).
#include "structloc/slam_core/pose_graph.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>
#include <string>

#include "pose_graph_problem.hpp"
#include "serial_openmp_scope.hpp"

namespace structloc::slam_core {
namespace {

// The measured pose of `to` in the frame of `from`, against the estimate:
// the residual, weighted by the square root of the edge's information.
struct RelativePoseError {
  RelativePoseError(const geometry::Pose2D& measured, const Eigen::Matrix3d& sqrt_information)
      : measured_(measured), sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* const from, const T* const to, T* residual) const {
    const T dx = to[0] - from[0];
    const T dy = to[1] - from[1];
    const T c = ceres::cos(from[2]);
    const T s = ceres::sin(from[2]);
    const T dtheta = to[2] - from[2] - T(measured_.theta);
    Eigen::Matrix<T, 3, 1> e;
    e(0) = c * dx + s * dy - T(measured_.x);
    e(1) = -s * dx + c * dy - T(measured_.y);
    e(2) = ceres::atan2(ceres::sin(dtheta), ceres::cos(dtheta));
    const Eigen::Matrix<T, 3, 1> weighted = sqrt_information_.cast<T>() * e;
    for (int i = 0; i < 3; ++i) residual[i] = weighted(i);
    return true;
  }

  geometry::Pose2D measured_;
  Eigen::Matrix3d sqrt_information_;
};

Eigen::Matrix3d SqrtInformation(const Eigen::Matrix3d& information) {
  // Upper factor U with U^T U = information: |U e|^2 = e^T information e.
  return Eigen::LLT<Eigen::Matrix3d>(information).matrixU();
}

void Check(int n, const PoseGraphEdge& e) {
  if (e.from < 0 || e.to < 0 || e.from >= n || e.to >= n || e.from == e.to)
    throw std::invalid_argument("pose graph: an edge joins poses " + std::to_string(e.from) +
                                " and " + std::to_string(e.to) + " of " + std::to_string(n));
  if (!e.information.allFinite() || !geometry::IsFinite(e.measured) ||
      Eigen::LLT<Eigen::Matrix3d>(e.information).info() != Eigen::Success)
    throw std::invalid_argument("pose graph: the edge from " + std::to_string(e.from) + " to " +
                                std::to_string(e.to) +
                                " has a measurement or information that is not finite and "
                                "positive definite");
}

}  // namespace

double EdgeError(const std::vector<geometry::Pose2D>& poses, const PoseGraphEdge& edge) {
  const RelativePoseError error(edge.measured, SqrtInformation(edge.information));
  const double from[3] = {poses[edge.from].x, poses[edge.from].y, poses[edge.from].theta};
  const double to[3] = {poses[edge.to].x, poses[edge.to].y, poses[edge.to].theta};
  double r[3];
  error(from, to, r);
  return std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
}

namespace internal {

PoseBlocks ToBlocks(const std::vector<geometry::Pose2D>& poses) {
  PoseBlocks x(poses.size());
  for (size_t i = 0; i < poses.size(); ++i) x[i] = {poses[i].x, poses[i].y, poses[i].theta};
  return x;
}

void FromBlocks(const PoseBlocks& blocks, std::vector<geometry::Pose2D>& poses) {
  for (size_t i = 0; i < poses.size(); ++i)
    poses[i] = {blocks[i][0], blocks[i][1], geometry::WrapAngle(blocks[i][2])};
}

void AddEdges(const std::vector<PoseGraphEdge>& edges, const PoseGraphOptions& options,
              ceres::Problem& problem, PoseBlocks& blocks) {
  for (const auto& e : edges) {
    Check(static_cast<int>(blocks.size()), e);
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseError, 3, 3, 3>(
        new RelativePoseError(e.measured, SqrtInformation(e.information)));
    ceres::LossFunction* loss =
        e.robust ? new ceres::CauchyLoss(options.robust_scale_sigmas) : nullptr;
    problem.AddResidualBlock(cost, loss, blocks[e.from].data(), blocks[e.to].data());
  }
}

ceres::Solver::Summary Solve(const PoseGraphOptions& options, ceres::Problem& problem,
                             PoseBlocks& blocks) {
  if (problem.HasParameterBlock(blocks[0].data()))
    problem.SetParameterBlockConstant(blocks[0].data());
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options.max_iterations;
  solver.num_threads = 1;
  ceres::Solver::Summary result;
  const SerialOpenMpScope one_thread_for_cholmod;
  ceres::Solve(solver, &problem, &result);
  return result;
}

}  // namespace internal

PoseGraphSummary OptimisePoseGraph(std::vector<geometry::Pose2D>& poses,
                                   const std::vector<PoseGraphEdge>& edges,
                                   const PoseGraphOptions& options) {
  PoseGraphSummary summary;
  if (poses.size() < 2 || edges.empty()) {
    summary.usable = true;
    return summary;
  }
  internal::PoseBlocks x = internal::ToBlocks(poses);
  ceres::Problem problem;
  internal::AddEdges(edges, options, problem, x);
  const ceres::Solver::Summary result = internal::Solve(options, problem, x);
  internal::FromBlocks(x, poses);
  summary.iterations = static_cast<int>(result.iterations.size());
  summary.initial_cost = result.initial_cost;
  summary.final_cost = result.final_cost;
  summary.usable = result.IsSolutionUsable();
  return summary;
}

}  // namespace structloc::slam_core
