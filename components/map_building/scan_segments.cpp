// Per-scan segment extraction (see header).
#include "structloc/map_building/scan_segments.hpp"

#include <cmath>

#include "structloc/fitting/line_fit.hpp"

namespace structloc::map_building {
namespace {

using fitting::FitLine;
using fitting::LineEstimate;
using fitting::LineSums;

struct GrowingLine {
  Eigen::Vector2d origin;
  LineSums sums;
  void Add(const Eigen::Vector2d& p) { sums.Add(p.x() - origin.x(), p.y() - origin.y()); }
  LineEstimate Fit() const { return FitLine(sums, origin.x(), origin.y()); }
};

}  // namespace

std::vector<ScanSegment> ExtractScanSegments(const std::vector<Eigen::Vector2d>& points,
                                             const ScanSegmentOptions& options) {
  std::vector<ScanSegment> segments;
  const size_t n = points.size();
  const size_t w = static_cast<size_t>(std::max(options.window_points, 2));
  size_t i = 0;
  while (i + w <= n) {
    GrowingLine line{points[i], {}};
    bool seed_ok = true;
    for (size_t k = i; k < i + w; ++k) {
      if (k > i && (points[k] - points[k - 1]).norm() > options.max_point_gap_m) seed_ok = false;
      line.Add(points[k]);
    }
    LineEstimate fit = line.Fit();
    if (!seed_ok || fit.degenerate ||
        std::sqrt(fit.sse / static_cast<double>(w)) > options.max_window_rms_m) {
      ++i;
      continue;
    }
    size_t j = i + w;
    while (j < n && (points[j] - points[j - 1]).norm() <= options.max_point_gap_m &&
           fit.DistanceTo(points[j].x(), points[j].y()) <= options.max_point_distance_m) {
      line.Add(points[j]);
      fit = line.Fit();
      ++j;
    }
    const bool long_enough = static_cast<int>(j - i) >= options.min_points &&
                             (points[j - 1] - points[i]).norm() >= options.min_length_m;
    if (long_enough) {
      segments.push_back({i, j});
      i = j;
    } else {
      ++i;
    }
  }
  return segments;
}

}  // namespace structloc::map_building
