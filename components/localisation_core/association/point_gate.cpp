// The Mahalanobis gate of point features (see header).
#include "structloc/localisation_core/association/point_gate.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace structloc::localisation_core {

bool GatePoint(const Eigen::Vector2d& measured, Eigen::Matrix2d& covariance,
               const Eigen::Vector2d& world, const geometry::Pose2D& prior,
               const Eigen::Matrix3d& prior_covariance, double map_sigma_m, double gate_chi2,
               double map_error_scale) {
  const Eigen::Matrix2d map = map_sigma_m * map_sigma_m * Eigen::Matrix2d::Identity();
  if (gate_chi2 > 0.0) {
    const double c = std::cos(prior.theta), s = std::sin(prior.theta);
    const double dx = world.x() - prior.x, dy = world.y() - prior.y;
    const Eigen::Vector2d predicted(c * dx + s * dy, -s * dx + c * dy);
    // d(predicted)/d(x, y, theta), as in the weighted solver's point rows.
    Eigen::Matrix<double, 2, 3> j;
    j << -c, -s, -s * dx + c * dy, s, -c, -c * dx - s * dy;
    const Eigen::Matrix2d innovation_cov = j * prior_covariance * j.transpose() + covariance + map;
    const Eigen::Vector2d nu = measured - predicted;
    if (!(nu.dot(innovation_cov.ldlt().solve(nu)) <= gate_chi2)) return false;
  }
  covariance += map_error_scale * map;
  return true;
}

}  // namespace structloc::localisation_core
