// How well two paths of one log agree with its raw scans where the robot
// came back to a place, with no reference path: for scan pairs that both
// paths put within MAX_APART_M and 30 deg of each other but at least
// MIN_TRAVEL_M of travel apart (the same place on another pass), the later
// scan is put into the earlier one's frame by each path's relative pose and
// its points measured against the earlier scan's surfaces. Printed: the mean
// distance for each path (capped at 0.1 m) and in how many pairs each fits
// the better. Where a path is bent at the scale of rooms, its revisits do
// not fit; structloc_path_scan_fit asks the same of consecutive steps. Used
// to ask whether the corrected poses or a SLAM path is the more consistent
// with the scans over a whole building (issue 41).
//   structloc_revisit_fit LOG A.tum B.tum [MIN_TRAVEL_M=10] [MAX_APART_M=1.0]
// The paths hold robot poses at the log's laser stamps (as `structloc slam
// --poses-out`, `structloc replay --out` and `synthesise-odometry
// --truth-out` write them).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "scan_surface_fit.hpp"

namespace {

using structloc::geometry::Pose2D;
using LaserPoses = std::vector<std::optional<Pose2D>>;

constexpr double kMaxTurnRad = 0.5236;  // 30 deg: the two views still overlap mostly

// Cumulative distance the laser moved along `laser` up to each scan.
std::vector<double> Travelled(const LaserPoses& laser) {
  std::vector<double> travelled(laser.size(), 0.0);
  std::optional<Pose2D> last;
  for (size_t i = 0; i < laser.size(); ++i) {
    travelled[i] = i > 0 ? travelled[i - 1] : 0.0;
    if (!laser[i]) continue;
    if (last) travelled[i] += (laser[i]->Translation() - last->Translation()).norm();
    last = laser[i];
  }
  return travelled;
}

}  // namespace

int main(int argc, char** argv) {
  namespace geometry = structloc::geometry;
  namespace evaluation = structloc::evaluation;
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: structloc_revisit_fit LOG A.tum B.tum [MIN_TRAVEL_M=10] "
                 "[MAX_APART_M=1.0]\n");
    return 2;
  }
  try {
    const double min_travel_m = argc > 4 ? std::atof(argv[4]) : 10.0;
    const double max_apart_m = argc > 5 ? std::atof(argv[5]) : 1.0;
    const auto log = structloc::map_building::ReadPosedScans(argv[1], {});
    const auto a = evaluation::LaserPosesOnPath(log, structloc::log_formats::ReadTum(argv[2]));
    const auto b = evaluation::LaserPosesOnPath(log, structloc::log_formats::ReadTum(argv[3]));
    const auto travelled_a = Travelled(a), travelled_b = Travelled(b);
    // Scans i and j are a revisit on both paths.
    auto revisit = [&](size_t i, size_t j) {
      for (const auto* laser : {&a, &b}) {
        const auto& p = (*laser)[i];
        const auto& q = (*laser)[j];
        if (!p || !q || (p->Translation() - q->Translation()).norm() > max_apart_m ||
            std::abs(geometry::WrapAngle(q->theta - p->theta)) > kMaxTurnRad)
          return false;
      }
      return travelled_a[j] - travelled_a[i] >= min_travel_m &&
             travelled_b[j] - travelled_b[i] >= min_travel_m;
    };
    size_t pairs = 0, a_fits_better = 0, b_fits_better = 0;
    double sum_a = 0.0, sum_b = 0.0;
    // From every third scan, the first later scan that revisits its place.
    for (size_t i = 0; i < log.scans.size(); i += 3) {
      if (log.scans[i].points.empty()) continue;
      size_t j = i + 1;
      while (j < log.scans.size() && !revisit(i, j)) ++j;
      if (j >= log.scans.size() || log.scans[j].points.empty()) continue;
      const evaluation::EarlierScan earlier(log.scans[i].points);
      const double fit_a =
          earlier.MeanDistance(log.scans[j].points, geometry::Between(*a[i], *a[j]));
      const double fit_b =
          earlier.MeanDistance(log.scans[j].points, geometry::Between(*b[i], *b[j]));
      sum_a += fit_a;
      sum_b += fit_b;
      a_fits_better += fit_a < fit_b;
      b_fits_better += fit_b < fit_a;
      ++pairs;
    }
    if (pairs == 0)
      throw std::runtime_error("no place revisited after " + std::to_string(min_travel_m) +
                               " m of travel on both paths");
    const double n = static_cast<double>(pairs);
    std::printf(
        "%zu revisits (scans at least %.1f m of travel apart, within %.1f m on both paths): "
        "points off the earlier scan by A %.2f mm, B %.2f mm on average (capped at %.0f mm); "
        "A fits better in %zu, B in %zu\n",
        pairs, min_travel_m, max_apart_m, 1e3 * sum_a / n, 1e3 * sum_b / n, 1e3 * evaluation::kCapM,
        a_fits_better, b_fits_better);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "structloc_revisit_fit: %s\n", e.what());
    return 1;
  }
  return 0;
}
