// Straight pieces of one scan: the map builder's per-scan step. A segment
// starts where a window of consecutive points fits a line well (the thesis'
// window line fit, 3.5.2, EQ 18) and grows point by point, refitting by total
// least squares, while the next point stays close to the line and close to the
// previous point. DDS-free.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace structloc::map_building {

struct ScanSegmentOptions {
  int window_points = 7;               // points of the seed window (Table 6's line-fit window)
  double max_window_rms_m = 0.02;      // a seed window scattering more is not a wall
  double max_point_distance_m = 0.04;  // a point farther from the growing line ends the segment
  double max_point_gap_m = 0.4;  // consecutive points farther apart belong to different objects
  int min_points = 10;           // shorter runs are clutter
  double min_length_m = 0.3;     // walls are at least this long
};

// Indices [first, last) of a segment within the scan's point list.
struct ScanSegment {
  size_t first = 0;
  size_t last = 0;
};

// Segments of `points` (in beam order); every point belongs to at most one.
std::vector<ScanSegment> ExtractScanSegments(const std::vector<Eigen::Vector2d>& points,
                                             const ScanSegmentOptions& options);

}  // namespace structloc::map_building
