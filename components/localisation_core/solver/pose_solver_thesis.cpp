// The thesis' own solvers (see pose_solver.hpp): the linear system of EQ 11,
// 12 and 30 with equal weights, and the bisection of section 3.5.8.
#include <Eigen/Dense>
#include <cmath>

#include "structloc/localisation_core/solver/pose_solver.hpp"

namespace structloc::localisation_core {
namespace {

// theta = circular mean of alpha_W - alpha_R over the walls (EQ 9); the
// prior's theta when there are no walls.
double HeadingFromWalls(const SolveInput& in) {
  double c = 0.0, s = 0.0;
  for (const auto& w : *in.walls) {
    const double t = w.world_alpha - w.alpha;
    c += std::cos(t);
    s += std::sin(t);
  }
  return in.walls->empty() ? in.prior.theta : std::atan2(s, c);
}

// The world position of the sensor implied by a point measurement and theta (EQ 28, 29).
Eigen::Vector2d PositionFromPoint(const PointMeasurement& p, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {p.world.x() - (c * p.sensor.x() - s * p.sensor.y()),
          p.world.y() - (s * p.sensor.x() + c * p.sensor.y())};
}

void ResetOutput(const SolveInput& in, SolveOutput& out) {
  out.wall_used.assign(in.walls->size(), 1);
  out.point_used.assign(in.points->size(), 1);
  out.wall_residual.assign(in.walls->size(), 0.0);
  out.point_residual.assign(in.points->size(), 0.0);
  out.feature_information.setZero();
  out.converged = true;
  out.iterations = 1;
}

// Feature information for observability checks, with unit weights scaled by
// the given position and heading variances.
void FillInformation(const SolveInput& in, const geometry::Pose2D& pose, SolveOutput& out) {
  for (const auto& w : *in.walls) {
    Eigen::Matrix<double, 2, 3> j;
    j << std::cos(w.world_alpha), std::sin(w.world_alpha), 0, 0, 0, 1;
    out.feature_information += j.transpose() * w.covariance.inverse() * j;
  }
  for (const auto& p : *in.points) {
    const double c = std::cos(pose.theta), s = std::sin(pose.theta);
    const double dx = p.world.x() - pose.x, dy = p.world.y() - pose.y;
    Eigen::Matrix<double, 2, 3> j;
    j << c, s, -(-s * dx + c * dy), -s, c, -(-c * dx - s * dy);
    out.feature_information += j.transpose() * p.covariance.inverse() * j;
  }
}

void Residuals(const SolveInput& in, const geometry::Pose2D& pose, SolveOutput& out) {
  for (size_t i = 0; i < in.walls->size(); ++i) {
    const auto& w = (*in.walls)[i];
    out.wall_residual[i] = std::abs(
        w.r - (w.world_r - (pose.x * std::cos(w.world_alpha) + pose.y * std::sin(w.world_alpha))));
  }
  for (size_t i = 0; i < in.points->size(); ++i) {
    out.point_residual[i] =
        (PositionFromPoint((*in.points)[i], pose.theta) - pose.Translation()).norm();
  }
}

}  // namespace

void SolveThesisLinear(const SolveInput& in, const SolverOptions&, SolveOutput& out) {
  ResetOutput(in, out);
  const double theta = HeadingFromWalls(in);
  const size_t nw = in.walls->size(), np = in.points->size();
  Eigen::MatrixXd a(static_cast<Eigen::Index>(nw + 2 * np + 2), 2);
  Eigen::VectorXd b(a.rows());
  Eigen::Index row = 0;
  for (const auto& w : *in.walls) {  // EQ 10/11
    a.row(row) << std::cos(w.world_alpha), std::sin(w.world_alpha);
    b(row++) = w.world_r - w.r;
  }
  for (const auto& p : *in.points) {  // EQ 30 (corners), EQ 33/34 (cylinders)
    const Eigen::Vector2d q = PositionFromPoint(p, theta);
    a.row(row) << 1, 0;
    b(row++) = q.x();
    a.row(row) << 0, 1;
    b(row++) = q.y();
  }
  // EQ 12: odometry rows only where the features leave a direction open.
  Eigen::JacobiSVD<Eigen::MatrixXd> probe(a.topRows(row));
  const auto sv = probe.singularValues();
  if (row < 2 || sv.size() < 2 || sv(1) < 1e-3 * std::max(1.0, sv(0))) {
    a.row(row) << 1, 0;
    b(row++) = in.prior.x;
    a.row(row) << 0, 1;
    b(row++) = in.prior.y;
  }
  const auto used_a = a.topRows(row);
  const auto used_b = b.head(row);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(used_a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::Vector2d xy = svd.solve(used_b);
  out.pose = {xy.x(), xy.y(), geometry::WrapAngle(theta)};
  const Eigen::VectorXd res = used_a * xy - used_b;
  const double dof = std::max<double>(1.0, static_cast<double>(row) - 2.0);
  const double sigma2 = std::max(res.squaredNorm() / dof, 1e-6);
  out.covariance.setZero();
  out.covariance.topLeftCorner<2, 2>() = sigma2 * (used_a.transpose() * used_a).inverse();
  double spread = 0.0;
  for (const auto& w : *in.walls) {
    spread += std::pow(geometry::WrapAngle(w.world_alpha - w.alpha - theta), 2);
  }
  out.covariance(2, 2) =
      nw > 1 ? std::max(spread / (nw - 1.0) / nw, 1e-8) : in.prior_covariance(2, 2);
  out.chi2 = res.squaredNorm() / sigma2;
  out.dof = static_cast<int>(dof);
  FillInformation(in, out.pose, out);
  Residuals(in, out.pose, out);
}

void SolveBisection(const SolveInput& in, const SolverOptions& o, SolveOutput& out) {
  ResetOutput(in, out);
  const double theta = HeadingFromWalls(in);
  // dS_tot/dx and dS_tot/dy (EQ 41-44), equal weights as in the thesis.
  auto gradient = [&](double x, double y) {
    Eigen::Vector2d g(2.0 * (x - in.prior.x), 2.0 * (y - in.prior.y));
    for (const auto& w : *in.walls) {
      const double c = std::cos(w.world_alpha), s = std::sin(w.world_alpha);
      const double e = x * c + y * s - (w.world_r - w.r);
      g += 2.0 * e * Eigen::Vector2d(c, s);
    }
    for (const auto& p : *in.points) {
      // EQ 43: to the circle of radius |centre_R| around the centre; EQ 41: to a point.
      if (p.bisection == BisectionTerm::kDistance) {
        const Eigen::Vector2d d = Eigen::Vector2d(x, y) - p.world;
        const double dist = std::max(d.norm(), 1e-12);
        g += 2.0 * (dist - p.sensor.norm()) * d / dist;
      } else {
        g += 2.0 * (Eigen::Vector2d(x, y) - PositionFromPoint(p, theta));
      }
    }
    return g;
  };
  double x = in.prior.x, y = in.prior.y;
  for (int sweep = 0; sweep < 3; ++sweep) {
    for (int axis = 0; axis < 2; ++axis) {
      double lo = (axis == 0 ? in.prior.x : in.prior.y) - o.search_half_width_m;
      double hi = (axis == 0 ? in.prior.x : in.prior.y) + o.search_half_width_m;
      for (int it = 0; it < o.bisection_iterations; ++it) {
        const double mid = 0.5 * (lo + hi);
        const double gm = axis == 0 ? gradient(mid, y).x() : gradient(x, mid).y();
        (gm > 0.0 ? hi : lo) = mid;
      }
      (axis == 0 ? x : y) = 0.5 * (lo + hi);
    }
  }
  out.pose = {x, y, geometry::WrapAngle(theta)};
  out.iterations = 3 * 2 * o.bisection_iterations;
  FillInformation(in, out.pose, out);
  Residuals(in, out.pose, out);
  const Eigen::Matrix3d info = out.feature_information + in.prior_covariance.inverse();
  out.covariance = info.inverse();
}

}  // namespace structloc::localisation_core
