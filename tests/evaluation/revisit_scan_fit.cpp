// How well two paths of one log agree with its raw scans where the robot
// came back to a place, with no reference path: for scan pairs that both
// paths put within MAX_APART_M and 30 deg of each other but at least
// MIN_TRAVEL_M of travel apart (the same place on another pass), the later
// scan is put into the earlier one's frame by each path's relative pose and
// its points measured against the earlier scan's surfaces. Printed: the mean
// distance for each path (capped at 0.1 m), in how many pairs each fits the
// better, and the least mean a relative pose near them gives (a local search
// from the better fitting path's): how far each path is from the best the
// scans allow. Where a path is bent at the scale of rooms, its revisits do
// not fit; structloc_path_scan_fit asks the same of consecutive steps. Used
// to ask whether the corrected poses or a SLAM path is the more consistent
// with the scans over a whole building (issue 41).
//   structloc_revisit_fit LOG A.tum B.tum [MIN_TRAVEL_M=10] [MAX_APART_M=1.0]
// The paths hold robot poses at the log's laser stamps (as `structloc slam
// --poses-out`, `structloc replay --out` and `synthesise-odometry
// --truth-out` write them).
#include <algorithm>
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

// 30 deg: a 180 deg laser's two views of the place still overlap mostly.
constexpr double kMaxTurnRad = structloc::geometry::kPi / 6.0;

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

// The least mean distance of `later`'s points from `earlier`'s surfaces over
// relative poses near `start` (where it is `best`): a pattern search in x, y
// and heading with steps halved from 40 mm (and 8 mrad) to 2.5 mm (0.5 mrad).
double BestFit(const structloc::evaluation::EarlierScan& earlier,
               const std::vector<Eigen::Vector2d>& later, Pose2D start, double best) {
  for (double step_m = 0.04; step_m > 0.002; step_m /= 2.0) {
    for (bool moved = true; moved;) {
      moved = false;
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dtheta = -1; dtheta <= 1; ++dtheta) {
            if (dx == 0 && dy == 0 && dtheta == 0) continue;
            const Pose2D tried{start.x + dx * step_m, start.y + dy * step_m,
                               start.theta + dtheta * step_m / 5.0};
            const double fit = earlier.MeanDistance(later, tried);
            if (fit < best) best = fit, start = tried, moved = true;
          }
        }
      }
    }
  }
  return best;
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
    double sum_a = 0.0, sum_b = 0.0, sum_best = 0.0;
    // From every third scan, the first later scan that revisits its place.
    for (size_t i = 0; i < log.scans.size(); i += 3) {
      if (!a[i] || !b[i] || log.scans[i].points.empty()) continue;
      size_t j = i + 1;
      while (j < log.scans.size() && !revisit(i, j)) ++j;
      if (j >= log.scans.size() || log.scans[j].points.empty()) continue;
      const evaluation::EarlierScan earlier(log.scans[i].points);
      const Pose2D step_a = geometry::Between(*a[i], *a[j]);
      const Pose2D step_b = geometry::Between(*b[i], *b[j]);
      const double fit_a = earlier.MeanDistance(log.scans[j].points, step_a);
      const double fit_b = earlier.MeanDistance(log.scans[j].points, step_b);
      sum_best += BestFit(earlier, log.scans[j].points, fit_a <= fit_b ? step_a : step_b,
                          std::min(fit_a, fit_b));
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
        "A fits better in %zu, B in %zu; the best relative poses near them %.2f mm\n",
        pairs, min_travel_m, max_apart_m, 1e3 * sum_a / n, 1e3 * sum_b / n, 1e3 * evaluation::kCapM,
        a_fits_better, b_fits_better, 1e3 * sum_best / n);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "structloc_revisit_fit: %s\n", e.what());
    return 1;
  }
  return 0;
}
