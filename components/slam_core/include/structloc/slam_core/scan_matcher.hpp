// The SLAM front end's measurement: where a scan was taken relative to a
// reference (the points of the scans before it, or of a place seen long
// ago), by point-to-line ICP (Censi's PL-ICP idea: each point pulled onto
// the line through its nearest reference points, which converges far
// faster than point-to-point on walls), with the covariance the match
// supports and how much of the scan it explains, for the caller to refuse a
// poor match. DDS-free.
#pragma once

#include <Eigen/Core>
#include <unordered_map>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/slam_core/point_tree.hpp"

namespace structloc::slam_core {

struct ScanMatchOptions {
  int iterations = 30;
  // Pairs are sought this far first, then the distance shrinks to the last.
  double first_pair_distance_m = 1.0;
  double last_pair_distance_m = 0.2;
  double normal_radius_m = 0.25;  // reference neighbours that give a point's line
  double point_sigma_m = 0.03;    // a point's noise along the normal (range noise, walls)
  // Neighbouring points see the same stretch of wall, their errors are not
  // independent: the covariance counts one point in this many.
  double correlated_points = 10.0;
  double min_sigma_xy_m = 0.01;  // the covariance never claims better than these
  double min_sigma_theta_rad = 0.003;
  // Where the pairs pin one direction of the position only (a corridor), the
  // match keeps the guess's position along it instead of sliding, each
  // update solved in the directions pinned (solution remapping, Zhang, Kaess
  // and Singh 2016). Slam sets it for its step matches with partial matches.
  bool hold_unpinned = false;
};

struct ScanMatch {
  geometry::Pose2D pose;  // of the scan's frame in the reference's frame
  // Large along what the points do not pin (a corridor's length); identity
  // when too few points paired to say anything.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  double inlier_share = 0.0;  // of the scan's points within last_pair_distance_m of a line
  double rms_m = 0.0;         // of those points' distances
  int pairs = 0;
  bool constrained = false;  // every direction pinned (not a featureless corridor)
};

// Reference points with the direction of the surface through each, indexed
// for nearest-neighbour lookups. A point's surface (the line through its
// neighbours within normal_radius_m, or none where they do not lie along one)
// is found the first time a lookup needs it: an ICP touches a fraction of a
// submap's points, and finding every point's neighbours was most of a loop
// closure's work. So a lookup changes what the reference holds: one thread at
// a time (a copy for each further thread finds the same).
class ReferencePoints {
 public:
  ReferencePoints(const std::vector<Eigen::Vector2d>& points, const ScanMatchOptions& options);
  // The nearest point with a surface within `max_distance_m` of `p` (-1: none).
  int Nearest(const Eigen::Vector2d& p, double max_distance_m) const;
  const Eigen::Vector2d& Point(int i) const { return points_[i]; }
  // Of a point Nearest gave.
  const Eigen::Vector2d& Normal(int i) const { return normals_[i]; }

 private:
  enum class Surface : signed char { kUnknown, kNone, kLine };
  bool OnSurface(int i) const;

  std::vector<Eigen::Vector2d> points_;
  double normal_radius_m_;
  // The points by cells normal_radius_m wide, for a point's neighbours.
  std::unordered_map<long long, std::vector<int>> cells_;
  PointTree tree_;
  mutable std::vector<Surface> surface_;
  mutable std::vector<Eigen::Vector2d> normals_;
};

ScanMatch MatchScan(const ReferencePoints& reference, const std::vector<Eigen::Vector2d>& points,
                    const geometry::Pose2D& guess, const ScanMatchOptions& options = {});

}  // namespace structloc::slam_core
