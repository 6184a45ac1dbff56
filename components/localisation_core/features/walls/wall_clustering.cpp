// Wall clustering by expectation (see header).
#include "structloc/localisation_core/features/walls/wall_clustering.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace structloc::localisation_core {

namespace {

// The map's angle error of a wall: map_sigma_alpha_rad, but never so much
// that the wall's ends err by more than its offset error again (long walls
// are drawn or fitted with proportionally better angles).
double MapAngleSigma(const WallClusterOptions& o, const ExpectedExtent* wall) {
  if (wall == nullptr || wall->wall_half_length <= 0.0) return o.map_sigma_alpha_rad;
  return std::min(o.map_sigma_alpha_rad, o.map_sigma_r_m / wall->wall_half_length);
}

// Variance of a map wall's offset `lever_m` along the line from its centre:
// offset error plus the angle error over the lever arm.
double MapOffsetVariance(const WallClusterOptions& o, const ExpectedExtent* wall, double lever_m) {
  const double sa = MapAngleSigma(o, wall) * lever_m;
  return o.map_sigma_r_m * o.map_sigma_r_m + sa * sa;
}

// The sensor pose with the cosine and sine of its heading.
struct SensorPose {
  explicit SensorPose(const geometry::Pose2D& p)
      : pose(p), c(std::cos(p.theta)), s(std::sin(p.theta)) {}
  const geometry::Pose2D& pose;
  double c, s;
};

// Along-line (world) coordinate of a sensor-frame point seen from `sensor`.
double AlongLine(const ExpectedWall& x, const SensorPose& sensor, double px, double py) {
  const auto& pose = sensor.pose;
  const double pc = sensor.c, ps = sensor.s;
  const double wx = pose.x + pc * px - ps * py;
  const double wy = pose.y + ps * px + pc * py;
  return -x.world_s * wx + x.world_c * wy;
}

// The walls that may pass the (r, alpha) gates of any window line close to a
// reference line: the gates widened by how far such a line may be from the
// reference (triangle inequality in r and in the angle between lines).
// Scan-ordered windows on one wall reuse the list, so that most windows test
// one or two walls instead of all (the result is the same). The slack is
// twice the gates: a short window's (r, alpha) scatters by about a gate at
// long range, and the list stays a list of the walls nearby.
class GateCandidates {
 public:
  GateCandidates(const WallClusterOptions& o, std::vector<int>& list)
      : list_(list),
        slack_r_(2.0 * o.gate_r_m),
        // Below pi/2 together with the gate: a window and its reference then
        // face every candidate from the same side, so that r's sign agrees.
        slack_alpha_(
            std::min(2.0 * o.gate_alpha_rad, 0.5 * (geometry::kHalfPi - o.gate_alpha_rad))),
        min_dot_(std::cos(std::min(o.gate_alpha_rad + slack_alpha_, geometry::kHalfPi)) - 1e-12),
        max_dr_(o.gate_r_m + slack_r_ + 1e-12),
        near_dot_(std::cos(slack_alpha_)) {}

  // The candidates for line `l`, recomputed when `l` is not near the reference.
  const std::vector<int>& For(const LineEstimate& l, const ExpectedWalls& expected) {
    const bool near =
        has_reference_ && std::abs(l.r - reference_.r) <= slack_r_ &&
        l.cos_alpha * reference_.cos_alpha + l.sin_alpha * reference_.sin_alpha >= near_dot_;
    if (near) return list_;
    has_reference_ = true;
    reference_ = l;
    list_.clear();
    for (size_t e = 0; e < expected.walls.size(); ++e) {
      const LineOffset off = OffsetFrom(l, expected.walls[e]);
      if (off.dot >= min_dot_ && std::abs(off.dr) <= max_dr_) list_.push_back(static_cast<int>(e));
    }
    return list_;
  }

 private:
  std::vector<int>& list_;
  const double slack_r_, slack_alpha_, min_dot_, max_dr_, near_dot_;
  bool has_reference_ = false;
  LineEstimate reference_;
};

}  // namespace

void AssignWindowsByExpectation(const std::vector<WindowLine>& windows,
                                const ExpectedWalls& expected, const geometry::Pose2D& pose,
                                const Eigen::Matrix3d& cov, const WallClusterOptions& o,
                                WallClusterWork& work, std::vector<int>& assignment) {
  assignment.assign(windows.size(), -1);
  if (expected.walls.empty()) return;
  const WallGate gate(o);
  const SensorPose sensor(pose);
  const double pc = sensor.c, ps = sensor.s;
  const bool check_extent = o.extent_margin_m > 0.0;
  const bool mahalanobis = o.gate_chi2 > 0.0;
  const double floor2 = o.min_point_sigma_m * o.min_point_sigma_m;
  GateCandidates candidates(o, work.gate_candidates);
  for (size_t i = 0; i < windows.size(); ++i) {
    const auto& w = windows[i];
    if (!w.valid) continue;
    const auto& l = w.line;
    // The window's centroid in the world: the overlap test and the gate use it.
    const Eigen::Vector2d v(pc * l.xm - ps * l.ym, ps * l.xm + pc * l.ym);  // R p
    int best = -1;
    double best_d = 3.0;  // > 2 = outside both gates
    for (const int candidate : candidates.For(l, expected)) {
      const auto e = static_cast<size_t>(candidate);
      const auto& x = expected.walls[e];
      double d;
      if (!gate.Nearer(OffsetFrom(l, x), best_d, &d)) continue;
      if (check_extent || mahalanobis) {
        const double t = -x.world_s * (pose.x + v.x()) + x.world_c * (pose.y + v.y());
        const ExpectedExtent* wall = nullptr;
        const double outside = expected.DistanceOutside(static_cast<int>(e), t, &wall);
        if (check_extent && outside > o.extent_margin_m) continue;
        const double centre = wall != nullptr ? wall->wall_centre : t;
        if (mahalanobis) {
          const double off = l.xm * x.c + l.ym * x.s - x.r;  // centroid from the line
          const Eigen::Vector3d j(x.world_c, x.world_s, -v.y() * x.world_c + v.x() * x.world_s);
          const double var =
              j.dot(cov * j) + std::max(l.sse, floor2) + MapOffsetVariance(o, wall, t - centre);
          if (off * off > o.gate_chi2 * var) continue;
        }
      }
      best = candidate;
      best_d = d;
    }
    assignment[i] = best;
  }
}

namespace {

// The map's error of expected wall `e` at a cluster's place, over (r, alpha),
// and how far that place lies outside the wall's visible extents.
struct MapErrorAt {
  Eigen::Matrix2d covariance;
  double outside_m;
};
MapErrorAt MapErrorOf(const WallCluster& c, const ExpectedWalls& expected, int e,
                      const SensorPose& sensor, const WallClusterOptions& o) {
  const auto& x = expected.walls[static_cast<size_t>(e)];
  const double t = AlongLine(x, sensor, c.centroid.x(), c.centroid.y());
  const ExpectedExtent* wall = nullptr;
  const double outside = expected.DistanceOutside(e, t, &wall);
  const double centre = wall != nullptr ? wall->wall_centre : t;
  // The sensor's foot on the line: the offset error at the sensor's own
  // along-line place is what r measures (thesis EQ 23 with an uncertain r_W, alpha_W).
  const double t_sensor = -x.world_s * sensor.pose.x + x.world_c * sensor.pose.y;
  const double lever = centre - t_sensor;
  const double sa = MapAngleSigma(o, wall);
  Eigen::Matrix2d m;
  m << MapOffsetVariance(o, wall, lever), lever * sa * sa, lever * sa * sa, sa * sa;
  return {m, outside};
}

// Squared Mahalanobis distance of a cluster from expected wall `e`, with the
// map's error at the cluster's place (`map_cov`).
double ClusterDistance(const WallCluster& c, const ExpectedWalls& expected, int e,
                       const Eigen::Matrix2d& map_cov, const Eigen::Matrix3d& cov) {
  const auto& x = expected.walls[static_cast<size_t>(e)];
  double r = c.refined_r, alpha = c.refined_alpha;
  if (std::cos(alpha) * x.c + std::sin(alpha) * x.s < 0.0) {
    r = -r;
    alpha += geometry::kPi;
  }
  Eigen::Matrix<double, 2, 3> h;
  h << -x.world_c, -x.world_s, 0.0, 0.0, 0.0, -1.0;
  const Eigen::Matrix2d s = h * cov * h.transpose() + c.covariance + map_cov;
  const Eigen::Vector2d nu(r - x.r, geometry::WrapAngle(alpha - std::atan2(x.s, x.c)));
  return nu.dot(s.ldlt().solve(nu));
}

}  // namespace

void GateWallClusters(const ExpectedWalls& expected, const geometry::Pose2D& pose,
                      const Eigen::Matrix3d& cov, const WallClusterOptions& o,
                      std::vector<WallCluster>& clusters) {
  const double min_dot = std::cos(o.gate_alpha_rad);
  const SensorPose sensor(pose);
  const bool gate = o.gate_chi2 > 0.0;
  size_t kept = 0;
  for (size_t k = 0; k < clusters.size(); ++k) {
    WallCluster c = clusters[k];
    const auto& mine = expected.walls[static_cast<size_t>(c.expected_index)];
    const Eigen::Matrix2d map_cov = MapErrorOf(c, expected, c.expected_index, sensor, o).covariance;
    bool keep =
        !gate || ClusterDistance(c, expected, c.expected_index, map_cov, cov) <= o.gate_chi2;
    for (size_t f = 0; keep && gate && f < expected.walls.size(); ++f) {
      if (static_cast<int>(f) == c.expected_index) continue;
      const auto& x = expected.walls[f];
      if (std::abs(x.c * mine.c + x.s * mine.s) < min_dot) continue;  // not parallel
      const auto f_index = static_cast<int>(f);
      const MapErrorAt f_error = MapErrorOf(c, expected, f_index, sensor, o);
      if (o.extent_margin_m > 0.0 && f_error.outside_m > o.extent_margin_m) continue;
      if (ClusterDistance(c, expected, f_index, f_error.covariance, cov) <= o.gate_chi2) {
        keep = false;  // two walls explain it: ambiguous
      }
    }
    if (!keep) continue;
    // The map's error, counted once over the scans that share it (map_error_memory.hpp).
    c.covariance += mine.map_error_scale * map_cov;
    clusters[kept++] = c;
  }
  clusters.resize(kept);
}

void WallClusterWork::Reserve(size_t points, size_t expected) {
  gate_candidates.reserve(expected);
  point_label.reserve(points);
  sums.reserve(expected);
  windows.reserve(expected);
}

void BuildWallClusters(const std::vector<WindowLine>& windows, const std::vector<int>& assignment,
                       const ScanPoints& points, int window_points, const ExpectedWalls& expected,
                       const WallClusterOptions& o, ClusterMeans means, WallClusterWork& work,
                       std::vector<WallCluster>& out) {
  out.clear();
  const size_t ne = expected.walls.size();
  const size_t np = points.Size();
  work.sums.assign(ne, LineSums{});
  work.windows.assign(ne, WallClusterWork::WindowSums{});
  work.point_label.assign(np, -1);
  // A run of windows of one wall is summed in a local copy (the same
  // additions in the same order, without a store and reload per window).
  int run_wall = -1;
  WallClusterWork::WindowSums run_windows;
  for (size_t i = 0; i < windows.size(); ++i) {
    const int e = assignment[i];
    if (e < 0) continue;
    if (e != run_wall) {
      if (run_wall >= 0) work.windows[static_cast<size_t>(run_wall)] = run_windows;
      run_wall = e;
      run_windows = work.windows[static_cast<size_t>(e)];
    }
    if (means == ClusterMeans::kCompute) {
      const auto& x = expected.walls[static_cast<size_t>(e)];
      const auto& l = windows[i].line;
      const double sign = (l.cos_alpha * x.c + l.sin_alpha * x.s) < 0.0 ? -1.0 : 1.0;
      run_windows.r += sign * l.r;
      run_windows.c += sign * l.cos_alpha;
      run_windows.s += sign * l.sin_alpha;
    }
    ++run_windows.count;
    // Windows come in scan order, so the points of this window before
    // labelled_end already carry label e: label each point once per run.
    const size_t first = static_cast<size_t>(windows[i].first);
    const size_t end = first + static_cast<size_t>(window_points);
    for (size_t u = std::max(first, run_windows.labelled_end); u < end; ++u) {
      int& label = work.point_label[u < np ? u : u - np];
      label = (label == -1 || label == e) ? e : -2;  // -2: claimed by two walls
    }
    run_windows.labelled_end = std::max(run_windows.labelled_end, end);
  }
  if (run_wall >= 0) work.windows[static_cast<size_t>(run_wall)] = run_windows;
  // Sums relative to each cluster's first point would be ideal; the sensor
  // origin is close enough for indoor ranges in double precision. A run of
  // points of one wall is summed in a local copy (the same additions in the
  // same order, without a store and reload per point).
  int run_label = -1;
  LineSums run;
  for (size_t k = 0; k < np; ++k) {
    const int e = work.point_label[k];
    if (e != run_label) {
      if (run_label >= 0) work.sums[static_cast<size_t>(run_label)] = run;
      run_label = e;
      if (e >= 0) run = work.sums[static_cast<size_t>(e)];
    }
    if (e >= 0) run.Add(points.x[k], points.y[k]);
  }
  if (run_label >= 0) work.sums[static_cast<size_t>(run_label)] = run;
  const double floor2 = o.min_point_sigma_m * o.min_point_sigma_m;
  for (size_t e = 0; e < ne; ++e) {
    const int n = work.windows[e].count;
    if (n < o.min_cluster_size || work.sums[e].n < 3) continue;
    const auto& x = expected.walls[e];
    WallCluster cl;
    cl.expected_index = static_cast<int>(e);
    cl.members = n;
    if (means == ClusterMeans::kCompute) {
      cl.mean_r = work.windows[e].r / n;
      cl.mean_alpha = std::atan2(work.windows[e].s, work.windows[e].c);
    }
    const LineEstimate fit = FitLine(work.sums[e], 0.0, 0.0);
    if (fit.degenerate) continue;
    const double sign = (fit.cos_alpha * x.c + fit.sin_alpha * x.s) < 0.0 ? -1.0 : 1.0;
    const double c = sign * fit.cos_alpha, s = sign * fit.sin_alpha;
    cl.refined_r = sign * fit.r;
    cl.refined_alpha = std::atan2(s, c);
    cl.points = static_cast<int>(work.sums[e].n);
    cl.centroid = Eigen::Vector2d(fit.xm, fit.ym);
    // Residual e_k = x_k c + y_k s - r: d/dr = -1, d/dalpha = t_k (along-line coordinate).
    const double npts = work.sums[e].n;
    const double sigma2 = std::max(fit.sse / std::max(1.0, npts - 2.0), floor2);
    const double tm = -fit.xm * s + fit.ym * c;
    Eigen::Matrix2d info;
    info << npts, -npts * tm, -npts * tm, fit.along_spread + npts * tm * tm;
    cl.covariance = sigma2 * info.inverse();
    out.push_back(cl);
  }
}

}  // namespace structloc::localisation_core
