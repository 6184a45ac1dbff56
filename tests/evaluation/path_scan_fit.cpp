// How well a path's steps fit the raw scans of its log, with no reference
// path: for scan pairs a given distance apart along the path, the later
// scan is put into the earlier one's frame by the path's relative pose and
// each of its points measured against the line through the earlier scan's
// nearest point and that point's neighbour. Printed: the mean distance
// (capped at 0.1 m, so that what one scan sees and the other does not counts
// alike), and the scale of the path's relative translations the scans fit
// best (the path's rotations kept). A path whose steps are longer than the
// scans say prefers a scale below 1. Used to ask whether a reference path
// (the recordings' corrected poses) or an estimate (a SLAM path) agrees
// better with the scans (issue 41).
//   structloc_path_scan_fit LOG PATH.tum [MIN_M=1.0] [MAX_M=1.5]
// PATH.tum holds robot poses at the log's laser stamps (as `structloc slam
// --poses-out`, `structloc replay --out` and `synthesise-odometry --truth-out`
// write them); the log's laser lines give the laser's mounting.
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "scan_surface_fit.hpp"

int main(int argc, char** argv) {
  namespace geometry = structloc::geometry;
  using geometry::Pose2D;
  if (argc < 3) {
    std::fprintf(stderr, "usage: structloc_path_scan_fit LOG PATH.tum [MIN_M=1.0] [MAX_M=1.5]\n");
    return 2;
  }
  try {
    const double min_m = argc > 3 ? std::atof(argv[3]) : 1.0;
    const double max_m = argc > 4 ? std::atof(argv[4]) : 1.5;
    const auto log = structloc::map_building::ReadPosedScans(argv[1], {});
    const auto laser =
        structloc::evaluation::LaserPosesOnPath(log, structloc::log_formats::ReadTum(argv[2]));
    constexpr int kScales = 17;  // 0.98 .. 1.02
    auto scale_of = [](int k) { return 0.98 + 0.0025 * k; };
    std::vector<double> mean_at(kScales, 0.0);
    size_t pairs = 0;
    for (size_t i = 0; i < log.scans.size(); i += 3) {
      if (!laser[i] || log.scans[i].points.empty()) continue;
      size_t j = i + 1;
      auto apart = [&](size_t k) {
        return (laser[k]->Translation() - laser[i]->Translation()).norm();
      };
      while (j < log.scans.size() && (!laser[j] || apart(j) < min_m)) ++j;
      if (j >= log.scans.size() || apart(j) > max_m || log.scans[j].points.empty()) continue;
      const Pose2D step = geometry::Between(*laser[i], *laser[j]);
      const structloc::evaluation::EarlierScan earlier(log.scans[i].points);
      for (int k = 0; k < kScales; ++k) {
        const Pose2D scaled{step.x * scale_of(k), step.y * scale_of(k), step.theta};
        mean_at[k] += earlier.MeanDistance(log.scans[j].points, scaled);
      }
      ++pairs;
    }
    if (pairs == 0)
      throw std::runtime_error("no scan pairs " + std::to_string(min_m) + "-" +
                               std::to_string(max_m) + " m apart on the path");
    int best = 0;
    for (int k = 1; k < kScales; ++k) {
      if (mean_at[k] < mean_at[best]) best = k;
    }
    // The minimum refined by a parabola through it and its neighbours.
    double preferred = scale_of(best);
    if (best > 0 && best < kScales - 1) {
      const double a = mean_at[best - 1], b = mean_at[best], c = mean_at[best + 1];
      const double curvature = a - 2.0 * b + c;
      if (curvature > 0.0) preferred += 0.0025 * 0.5 * (a - c) / curvature;
    }
    const int unscaled = 8;
    std::printf(
        "%zu scan pairs %.1f-%.1f m apart: points off the earlier scan by %.2f mm on average "
        "(capped at %.0f mm); the scans fit the path's translations best scaled by %.4f "
        "(%.2f mm)%s\n",
        pairs, min_m, max_m, 1e3 * mean_at[unscaled] / static_cast<double>(pairs),
        1e3 * structloc::evaluation::kCapM, preferred,
        1e3 * mean_at[best] / static_cast<double>(pairs),
        best == 0 || best == kScales - 1 ? " (at the end of the range tried: 0.98-1.02)" : "");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "structloc_path_scan_fit: %s\n", e.what());
    return 1;
  }
  return 0;
}
