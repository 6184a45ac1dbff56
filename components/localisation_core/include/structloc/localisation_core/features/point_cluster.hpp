// A cluster of point estimates (corner intersections, circle centres) in the
// sensor frame around one expected point, with its mean and covariance.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "structloc/localisation_core/scan/line_fit.hpp"

namespace structloc::localisation_core {

struct PointCluster {
  int expected_index = 0;
  int members = 0;
  Eigen::Vector2d mean{0, 0};                                // thesis value: mean of the members
  Eigen::Vector2d refined{0, 0};                             // used by the weighted solver
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // of `refined`
};

// Running sums of 2-D points per expected feature (the same sums a line fit uses).
struct PointSums : LineSums {
  Eigen::Vector2d Mean() const { return {sx / n, sy / n}; }
  // Sample covariance of the points (not of their mean).
  Eigen::Matrix2d Scatter() const;
  // Cluster around expected point `index`: mean, and the covariance of the mean
  // counting one independent member per window length (overlapping windows make
  // members strongly correlated), plus a noise floor.
  PointCluster ToCluster(int index, int window_points, double sigma_floor_m) const;
};

// Index of the nearest expected point within `gate` of (x, y), or -1.
template <class Expected>
int NearestWithin(const std::vector<Expected>& expected, double x, double y, double gate2) {
  int best = -1;
  double best_d = gate2;
  for (size_t e = 0; e < expected.size(); ++e) {
    const double dx = x - expected[e].sensor.x(), dy = y - expected[e].sensor.y();
    const double d = dx * dx + dy * dy;
    if (d <= best_d) {
      best_d = d;
      best = static_cast<int>(e);
    }
  }
  return best;
}

}  // namespace structloc::localisation_core
