// Beyond the thesis' fixed distance gates (3.5.4, 3.5.6): a matched corner or
// pillar centre is kept only when it lies within a Mahalanobis gate of its
// expected position under the prior's covariance, its own and the map's, and
// its covariance then carries the map's error too. Shared by the point kinds.
#pragma once

#include <Eigen/Core>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::localisation_core {

// Whether `measured` (sensor frame, covariance `covariance`) may be the world
// point `world` seen from `prior` (covariance `prior_covariance`), with the
// map's error `map_sigma_m` per axis and a chi-square gate (2 dof; 0: none).
// Adds the map's error to `covariance` when it may, times `map_error_scale`
// (how often this scan's map error was fused already, map_error_memory.hpp;
// the gate itself uses the map's error once).
bool GatePoint(const Eigen::Vector2d& measured, Eigen::Matrix2d& covariance,
               const Eigen::Vector2d& world, const geometry::Pose2D& prior,
               const Eigen::Matrix3d& prior_covariance, double map_sigma_m, double gate_chi2,
               double map_error_scale = 1.0);

}  // namespace structloc::localisation_core
