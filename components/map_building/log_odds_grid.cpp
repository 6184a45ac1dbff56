// Log-odds occupancy grid by ray casting (see header).
#include "structloc/map_building/log_odds_grid.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "structloc/map_building/option_check.hpp"

namespace structloc::map_building {
namespace {

// Visits the cells of the straight line from cell a to cell b (Bresenham),
// calling pass(x, y) for all but the last and end(x, y) for b.
template <class Pass, class End>
void TraceCells(int x0, int y0, int x1, int y1, Pass pass, End end) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  while (x0 != x1 || y0 != y1) {
    pass(x0, y0);
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
  end(x1, y1);
}

// Bad options are refused as "log-odds grid option ...".
constexpr const char* kOptions = "log-odds grid";

void CheckOptions(const LogOddsGridOptions& o) {
  RequireOption(o.resolution_m > 0.0 && std::isfinite(o.resolution_m), kOptions,
                "resolution_m must be positive and finite");
  RequireOption(o.hit_log_odds > 0.0 && std::isfinite(o.hit_log_odds), kOptions,
                "hit_log_odds must be positive and finite");
  RequireOption(o.miss_log_odds < 0.0 && std::isfinite(o.miss_log_odds), kOptions,
                "miss_log_odds must be negative and finite");
  RequireOption(o.min_log_odds < 0.0, kOptions, "min_log_odds must be negative (-inf: no clamp)");
  RequireOption(o.max_log_odds > 0.0, kOptions, "max_log_odds must be positive (+inf: no clamp)");
  RequireOption(o.free_probability > 0.0 && o.free_probability < o.occupied_probability &&
                    o.occupied_probability < 1.0,
                kOptions,
                "free_probability and occupied_probability must satisfy 0 < free < occupied < 1");
}

double LogOdds(double p) {
  return std::log(p / (1.0 - p));
}

}  // namespace

map_building::OccupancyGrid RayCastGrid(const std::vector<PosedScan>& scans,
                                        const LogOddsGridOptions& options) {
  CheckOptions(options);
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const auto& scan : scans) {
    lo = lo.cwiseMin(scan.laser_pose.Translation());
    hi = hi.cwiseMax(scan.laser_pose.Translation());
    for (const auto& p : scan.points) {
      const Eigen::Vector2d m = scan.laser_pose.Apply(p);
      lo = lo.cwiseMin(m);
      hi = hi.cwiseMax(m);
    }
  }
  if (scans.empty()) throw std::invalid_argument("log-odds grid: no scans");
  lo -= Eigen::Vector2d::Constant(options.margin_m);
  hi += Eigen::Vector2d::Constant(options.margin_m);
  const double columns = std::ceil((hi.x() - lo.x()) / options.resolution_m);
  const double rows = std::ceil((hi.y() - lo.y()) / options.resolution_m);
  if (!(columns * rows <= options.max_cells)) {
    std::ostringstream message;
    message << std::setprecision(3) << "log-odds grid: " << columns << " x " << rows
            << " cells is above the limit of " << options.max_cells
            << " (are the poses in metres? is the resolution right?)";
    throw std::invalid_argument(message.str());
  }
  map_building::OccupancyGrid grid(static_cast<int>(columns), static_cast<int>(rows),
                                   options.resolution_m, {lo.x(), lo.y(), 0.0});
  // In double: with the default +0.85 / -0.4 every value a cell can reach is a
  // multiple of 0.05, more than 0.01 from both thresholds, and the rounding of
  // millions of updates stays far below that: the scans' order cannot flip a
  // cell (in float it could, once the sums grow past a few hundred).
  std::vector<double> log_odds(grid.cells.size(), 0.0);
  const auto cell = [&](int x, int y) -> double& {
    return log_odds[static_cast<size_t>(y) * static_cast<size_t>(grid.width) +
                    static_cast<size_t>(x)];
  };
  const auto add = [&](int x, int y, double delta) {
    double& l = cell(x, y);
    l = std::clamp(l + delta, options.min_log_odds, options.max_log_odds);
  };
  std::vector<uint8_t> seen(grid.cells.size(), 0);
  const auto update = [&](int x, int y, double delta) {
    if (!grid.Contains(x, y)) return;  // never: the grid bounds every finite point
    add(x, y, delta);
    seen[static_cast<size_t>(y) * static_cast<size_t>(grid.width) + static_cast<size_t>(x)] = 1;
  };
  for (const auto& scan : scans) {
    if (!geometry::IsFinite(scan.laser_pose)) continue;
    const Eigen::Vector2i from = grid.CellOf(scan.laser_pose.Translation());
    for (const auto& p : scan.points) {
      const Eigen::Vector2d end = scan.laser_pose.Apply(p);
      // A point that is not finite is outside the bounds above, and its cell
      // index would be undefined: skipped (the log reader refuses such beams).
      if (!end.allFinite()) continue;
      const Eigen::Vector2i to = grid.CellOf(end);
      TraceCells(
          from.x(), from.y(), to.x(), to.y(),
          [&](int x, int y) { update(x, y, options.miss_log_odds); },
          [&](int x, int y) { update(x, y, options.hit_log_odds); });
    }
  }
  const double occupied = LogOdds(options.occupied_probability);
  const double free = LogOdds(options.free_probability);
  for (size_t i = 0; i < grid.cells.size(); ++i) {
    if (!seen[i]) continue;
    grid.cells[i] = log_odds[i] > occupied ? map_building::OccupancyGrid::kOccupied
                    : log_odds[i] < free   ? map_building::OccupancyGrid::kFree
                                           : map_building::OccupancyGrid::kUnknown;
  }
  return grid;
}

}  // namespace structloc::map_building
