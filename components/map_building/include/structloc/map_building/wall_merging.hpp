// The map builder's cross-scan step: scan segments (already in the map frame)
// that lie on the same line in (r, alpha) with overlapping or nearly touching
// extents are one wall. Each wall is finally refitted by total least squares
// over all its supporting points, split where no point supports it (doors), and
// kept only when enough scans saw it, it is smooth enough and long enough.
// DDS-free.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "structloc/fitting/line_fit.hpp"
#include "structloc/map_building/wall_fitting.hpp"

namespace structloc::map_building {

struct WallMergeOptions {
  double max_angle_rad = 0.05;      // ~3 deg between a segment and a wall's line
  double max_offset_m = 0.05;       // a segment's ends to the wall's line
  double max_extent_gap_m = 0.5;    // a segment's extent to the wall's, along the line
  double inlier_distance_m = 0.04;  // the final refit keeps points this close to the line
  double max_gap_m = 0.4;           // a wall is split where no point supports it this long
  int min_scans = 3;                // walls seen from fewer scans are dropped
  int min_points = 20;              // walls with fewer supporting points are dropped
  double max_rms_m = 0.03;          // rougher walls (bushes, clutter, glass) are dropped
  double min_length_m = 0.3;        // shorter walls are clutter
};

struct WallMergeReport {
  size_t segments = 0;       // segments added
  size_t candidates = 0;     // walls before the final merge
  size_t merged = 0;         // candidates merged into others
  size_t pieces = 0;         // walls after splitting at gaps
  size_t too_few_scans = 0;  // dropped, and why
  size_t too_few_points = 0;
  size_t too_rough = 0;
  size_t too_short = 0;
};

class WallAccumulator {
 public:
  explicit WallAccumulator(const WallMergeOptions& options);

  // One segment of scan `scan`, its points in the map frame (at least two),
  // seen from `viewpoint` (the laser's position, map frame).
  void Add(uint32_t scan, const Eigen::Vector2d& viewpoint,
           const std::vector<Eigen::Vector2d>& points);
  // The walls (with their support: points, distinct scans, RMS).
  std::vector<FittedWall> Walls(WallMergeReport& report) const;

 private:
  struct Candidate {
    Eigen::Vector2d origin{0, 0};
    fitting::LineSums sums;
    fitting::LineEstimate fit;
    Eigen::Vector2d low{0, 0}, high{0, 0};  // extreme supporting points along the line
    std::vector<Eigen::Vector2d> points;
    std::vector<uint32_t> scans;
  };
  bool Accepts(const Candidate& wall, const Eigen::Vector2d& first, const Eigen::Vector2d& last,
               double& score) const;
  static void Absorb(Candidate& wall, const std::vector<Eigen::Vector2d>& points,
                     const std::vector<uint32_t>& scans);
  void Keep(const std::vector<Eigen::Vector2d>& points, const std::vector<uint32_t>& scans,
            std::vector<FittedWall>& out, WallMergeReport& report) const;

  WallMergeOptions options_;
  std::vector<Candidate> candidates_;
  std::vector<Eigen::Vector2d> viewpoints_;  // by scan number
  size_t segments_ = 0;
};

}  // namespace structloc::map_building
