// Step 3 (thesis 3.5.3, EQ 23-25): window lines join the cluster of the nearest
// expected wall within the (r, alpha) gates; unmodelled obstacles form
// clusters nobody uses. Each cluster yields, on request, the thesis' value
// (mean r, circular-mean alpha) and, beyond the thesis, a refined line fitted
// through all member points with its covariance from the point scatter.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "structloc/localisation_core/expectation/expected_walls.hpp"
#include "structloc/localisation_core/scan/line_fit.hpp"

namespace structloc::localisation_core {

struct WallClusterOptions {
  double gate_r_m = 0.2;             // Table 6: size of cluster (r)
  double gate_alpha_rad = 0.2;       // Table 6: size of cluster (alpha)
  int min_cluster_size = 1;          // Table 6: minimum number of points in a cluster
  double extent_margin_m = 0.5;      // a window must lie within the visible part of one
                                     // map wall plus this margin (0 or less disables the check)
  double min_point_sigma_m = 0.002;  // floor of the per-point noise used for covariances
  // The map's own error (beyond the thesis, which takes the map as exact): offset
  // of a wall at its centre and its angle, 1 sigma. Added to every pairing's
  // covariance, the angle's share growing with the distance from the wall's centre.
  double map_sigma_r_m = 0.0;
  double map_sigma_alpha_rad = 0.0;
  // Mahalanobis gate (chi-square, 2 dof) of a window and of a cluster against its
  // expected wall under the prior's covariance, the measurement's and the map's;
  // a cluster that passes the gate of two walls is ambiguous and dropped.
  // 0 keeps the thesis' fixed gates only.
  double gate_chi2 = 0.0;
};

// A matched wall: the measurement in the sensor frame, oriented like its
// expected wall (r may be negative), and its uncertainty.
struct WallCluster {
  int expected_index = 0;
  int members = 0;          // window lines in the cluster
  double mean_r = 0.0;      // thesis value: mean of the members' r (ClusterMeans::kCompute)
  double mean_alpha = 0.0;  // thesis value: circular mean of the members' alpha (the same)
  double refined_r = 0.0;   // line through the member points
  double refined_alpha = 0.0;
  int points = 0;  // member points behind the refined line
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // of (refined_r, refined_alpha)
  Eigen::Vector2d centroid{0, 0};                            // of the member points
};

// A window line against an expected wall (thesis EQ 23-25): the |cos| of the
// angle between their normals and the difference in r, the window's normal
// flipped to face the wall's way when it points the other.
struct LineOffset {
  double dot;
  double dr;
};
inline LineOffset OffsetFrom(const LineEstimate& l, const ExpectedWall& x) {
  const double signed_dot = l.cos_alpha * x.c + l.sin_alpha * x.s;
  return {std::abs(signed_dot), std::copysign(l.r, signed_dot) - x.r};
}

// The thesis' fixed (r, alpha) gates as a normalised distance: each term is 1
// at its gate's edge (1 - cos(d) ~ d^2 / 2: no atan2).
struct WallGate {
  explicit WallGate(const WallClusterOptions& o)
      : min_dot(std::cos(o.gate_alpha_rad)),
        inv_r2(1.0 / (o.gate_r_m * o.gate_r_m)),
        inv_a2(2.0 / (o.gate_alpha_rad * o.gate_alpha_rad)) {}
  // The distance of a line at `off`, and whether it is inside both gates and
  // nearer than `best`: one test, so that the branch is taken about once per
  // window and predicted.
  bool Nearer(const LineOffset& off, double best, double* distance) const {
    const double dr2 = off.dr * off.dr * inv_r2;
    *distance = dr2 + (1.0 - off.dot) * inv_a2;
    return (off.dot >= min_dot) & (dr2 <= 1.0) & (*distance < best);
  }
  double min_dot, inv_r2, inv_a2;
};

// Scratch space for AssignWindowsByExpectation and BuildWallClusters, reused
// across updates.
struct WallClusterWork {
  std::vector<int> gate_candidates;  // expected walls near the current window lines
  std::vector<int> point_label;
  std::vector<LineSums> sums;  // per expected wall: of its points
  // Per expected wall: the sums of its window lines' r, cos and sin of alpha
  // (flipped like the wall), their count, and the points labelled so far.
  struct WindowSums {
    double r = 0.0, c = 0.0, s = 0.0;
    int count = 0;
    size_t labelled_end = 0;
  };
  std::vector<WindowSums> windows;
  void Reserve(size_t points, size_t expected);
};

// Window i -> expected wall index, or -1. Nearest (normalised) match wins.
// With options.gate_chi2 > 0 a window's centroid must also lie within that
// Mahalanobis gate of the expected line under `sensor_covariance` (the prior's).
void AssignWindowsByExpectation(const std::vector<WindowLine>& windows,
                                const ExpectedWalls& expected, const geometry::Pose2D& sensor_pose,
                                const Eigen::Matrix3d& sensor_covariance,
                                const WallClusterOptions& options, WallClusterWork& work,
                                std::vector<int>& assignment);

// Whether clusters carry the thesis' mean (r, alpha) of their window lines
// beside the refined line: the thesis' solvers read it, the weighted solver
// does not, and skipping it saves a pass over the window lines.
enum class ClusterMeans { kSkip, kCompute };

void BuildWallClusters(const std::vector<WindowLine>& windows, const std::vector<int>& assignment,
                       const ScanPoints& points, int window_points, const ExpectedWalls& expected,
                       const WallClusterOptions& options, ClusterMeans means, WallClusterWork& work,
                       std::vector<WallCluster>& out);

// Adds the map's error to each cluster's covariance and, with options.gate_chi2
// > 0, drops clusters outside the Mahalanobis gate of their expected wall or
// inside the gate of another (ambiguous), under the prior's covariance.
void GateWallClusters(const ExpectedWalls& expected, const geometry::Pose2D& sensor_pose,
                      const Eigen::Matrix3d& sensor_covariance, const WallClusterOptions& options,
                      std::vector<WallCluster>& clusters);

}  // namespace structloc::localisation_core
