// Weighted Gauss-Newton pose solver (see pose_solver.hpp).
#include <Eigen/Dense>
#include <cmath>

#include "structloc/localisation_core/solver/pose_solver.hpp"

namespace structloc::localisation_core {

void SolveOutput::Reserve(size_t walls, size_t points) {
  wall_residual.reserve(walls);
  wall_used.reserve(walls);
  point_residual.reserve(points);
  point_used.reserve(points);
  wall_direction.reserve(walls);
  wall_information.reserve(walls);
  point_information.reserve(points);
}

namespace {

struct Row2 {
  Eigen::Vector2d residual;
  Eigen::Matrix<double, 2, 3> jacobian;
};

// Wall: measured (r, alpha) minus predicted (EQ 23, 24) at `pose`;
// `direction` is (cos, sin) of the wall's world angle.
Row2 WallRow(const WallMeasurement& m, const Eigen::Vector2d& direction,
             const geometry::Pose2D& pose) {
  const double cw = direction.x(), sw = direction.y();
  Row2 row;
  row.residual << m.r - (m.world_r - (pose.x * cw + pose.y * sw)),
      geometry::WrapAngle(m.alpha - (m.world_alpha - pose.theta));
  row.jacobian << cw, sw, 0.0, 0.0, 0.0, 1.0;
  return row;
}

// Point: measured sensor-frame position minus R(theta)^T (world - t);
// (c, s) are cos and sin of pose.theta.
Row2 PointRow(const PointMeasurement& m, const geometry::Pose2D& pose, double c, double s) {
  const double dx = m.world.x() - pose.x, dy = m.world.y() - pose.y;
  Row2 row;
  row.residual << m.sensor.x() - (c * dx + s * dy), m.sensor.y() - (-s * dx + c * dy);
  // d(predicted)/d(x, y, theta) = [[-c, -s, -s dx + c dy], [s, -c, -c dx - s dy]]
  row.jacobian << c, s, -(-s * dx + c * dy), -s, c, -(-c * dx - s * dy);
  return row;
}

}  // namespace

void SolveWeighted(const SolveInput& in, const SolverOptions& o, SolveOutput& out) {
  const auto& walls = *in.walls;
  const auto& points = *in.points;
  out.wall_used.assign(walls.size(), 1);
  out.point_used.assign(points.size(), 1);
  for (size_t i = 0; i < points.size(); ++i) out.point_used[i] = points[i].use_in_weighted;
  out.wall_residual.assign(walls.size(), 0.0);
  out.point_residual.assign(points.size(), 0.0);
  // What no iteration changes, once.
  out.wall_direction.resize(walls.size());
  out.wall_information.resize(walls.size());
  out.point_information.resize(points.size());
  for (size_t i = 0; i < walls.size(); ++i) {
    out.wall_direction[i] = {std::cos(walls[i].world_alpha), std::sin(walls[i].world_alpha)};
    out.wall_information[i] = walls[i].covariance.inverse();
  }
  for (size_t i = 0; i < points.size(); ++i) {
    out.point_information[i] = points[i].covariance.inverse();
  }
  const Eigen::Matrix3d prior_info = in.prior_covariance.inverse();
  geometry::Pose2D pose = in.prior;
  Eigen::Matrix3d h = prior_info;
  for (int pass = 0; pass < 4; ++pass) {  // re-solve after dropping outliers
    pose = in.prior;
    out.converged = false;
    for (int it = 0; it < o.max_iterations; ++it) {
      h = prior_info;
      out.feature_information.setZero();
      Eigen::Vector3d prior_res(pose.x - in.prior.x, pose.y - in.prior.y,
                                geometry::WrapAngle(pose.theta - in.prior.theta));
      Eigen::Vector3d g = prior_info * prior_res;  // gradient of 1/2 chi2
      for (size_t i = 0; i < walls.size(); ++i) {
        if (!out.wall_used[i]) continue;
        const Row2 row = WallRow(walls[i], out.wall_direction[i], pose);
        const Eigen::Matrix2d& w = out.wall_information[i];
        const Eigen::Matrix3d hi = row.jacobian.transpose() * w * row.jacobian;
        h += hi;
        out.feature_information += hi;
        g += row.jacobian.transpose() * w * row.residual;
      }
      const double c = std::cos(pose.theta), s = std::sin(pose.theta);
      for (size_t i = 0; i < points.size(); ++i) {
        if (!out.point_used[i]) continue;
        const Row2 row = PointRow(points[i], pose, c, s);
        const Eigen::Matrix2d& w = out.point_information[i];
        const Eigen::Matrix3d hi = row.jacobian.transpose() * w * row.jacobian;
        h += hi;
        out.feature_information += hi;
        g += row.jacobian.transpose() * w * row.residual;
      }
      const Eigen::Vector3d step = -h.ldlt().solve(g);
      if (!step.allFinite()) break;
      pose.x += step.x();
      pose.y += step.y();
      pose.theta = geometry::WrapAngle(pose.theta + step.z());
      out.iterations = it + 1;
      if (step.head<2>().norm() < 1e-9 && std::abs(step.z()) < 1e-10) {
        out.converged = true;
        break;
      }
    }
    // Residuals, chi-square and the worst outlier.
    double chi2 = 0.0;
    int rows = 3;
    double worst = o.outlier_chi2;
    int worst_wall = -1, worst_point = -1;
    for (size_t i = 0; i < walls.size(); ++i) {
      const Row2 row = WallRow(walls[i], out.wall_direction[i], pose);
      out.wall_residual[i] = std::abs(row.residual.x());
      if (!out.wall_used[i]) continue;
      const double m = row.residual.dot(out.wall_information[i] * row.residual);
      chi2 += m;
      rows += 2;
      if (m > worst) {
        worst = m;
        worst_wall = static_cast<int>(i);
        worst_point = -1;
      }
    }
    const double c = std::cos(pose.theta), s = std::sin(pose.theta);
    for (size_t i = 0; i < points.size(); ++i) {
      const Row2 row = PointRow(points[i], pose, c, s);
      out.point_residual[i] = row.residual.norm();
      if (!out.point_used[i]) continue;
      const double m = row.residual.dot(out.point_information[i] * row.residual);
      chi2 += m;
      rows += 2;
      if (m > worst) {
        worst = m;
        worst_point = static_cast<int>(i);
        worst_wall = -1;
      }
    }
    const Eigen::Vector3d prior_res(pose.x - in.prior.x, pose.y - in.prior.y,
                                    geometry::WrapAngle(pose.theta - in.prior.theta));
    chi2 += prior_res.dot(prior_info * prior_res);
    out.chi2 = chi2;
    out.dof = rows - 3;
    if (worst_wall >= 0) {
      out.wall_used[static_cast<size_t>(worst_wall)] = 0;
    } else if (worst_point >= 0) {
      out.point_used[static_cast<size_t>(worst_point)] = 0;
    } else {
      break;
    }
  }
  out.pose = pose;
  const double scale = out.dof > 0 ? std::max(1.0, out.chi2 / out.dof) : 1.0;
  out.covariance = scale * h.inverse();
}

void Solve(const SolveInput& input, const SolverOptions& options, SolveOutput& out) {
  switch (options.mode) {
    case SolverMode::kWeighted:
      return SolveWeighted(input, options, out);
    case SolverMode::kThesisLinear:
      return SolveThesisLinear(input, options, out);
    case SolverMode::kBisection:
      return SolveBisection(input, options, out);
  }
}

}  // namespace structloc::localisation_core
