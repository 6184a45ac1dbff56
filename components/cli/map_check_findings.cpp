// The findings of a map check, printed and drawn (see header).
#include "map_check_findings.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <numeric>

namespace structloc::cli {
namespace {

const cv::Scalar kAgrees(60, 160, 60);
const cv::Scalar kDisagrees(0, 0, 230);
const cv::Scalar kRarelySeen(0, 170, 255);
const cv::Scalar kNeverSeen(170, 170, 170);

void PrintDisagreeing(const world_model::WorldModel& world,
                      const map_building::MapCheckReport& report) {
  std::vector<size_t> order(report.walls.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return report.walls[a].median_m > report.walls[b].median_m;
  });
  std::cout << "  disagreeing walls (worst first; offset > 0: readings in front of the wall, "
               "move it towards the laser):\n    id  length_m  readings  scans  median_mm  "
               "offset_mm\n";
  size_t shown = 0;
  for (const size_t i : order) {
    const auto& a = report.walls[i];
    if (!a.disagrees) continue;
    if (shown++ == 20) break;
    const auto& w = world.Walls()[i];
    std::cout << std::setw(6) << w.id << std::setw(10) << std::setprecision(2) << w.Length()
              << std::setw(10) << a.readings << std::setw(7) << a.scans << std::setw(11)
              << std::setprecision(1) << 1000.0 * a.median_m << std::setw(11)
              << 1000.0 * a.mean_offset_m << "\n";
  }
  if (report.walls_disagreeing > 20)
    std::cout << "    ... and " << report.walls_disagreeing - 20 << " more\n";
  if (report.walls_never_seen == 0) return;
  std::cout << "  walls never seen:";
  size_t listed = 0;
  for (size_t i = 0; i < report.walls.size() && listed < 30; ++i) {
    if (report.walls[i].readings != 0) continue;
    std::cout << " " << world.Walls()[i].id;
    ++listed;
  }
  std::cout << (report.walls_never_seen > listed ? " ..." : "") << "\n";
}

std::vector<cv::Scalar> WallColours(const map_building::MapCheckReport& report,
                                    const map_building::MapCheckOptions& options) {
  std::vector<cv::Scalar> colours;
  for (const auto& a : report.walls) {
    colours.push_back(a.readings == 0                     ? kNeverSeen
                      : a.disagrees                       ? kDisagrees
                      : a.readings < options.min_readings ? kRarelySeen
                                                          : kAgrees);
  }
  return colours;
}

}  // namespace

void PrintMapCheckFindings(const world_model::WorldModel& world,
                           const map_building::MapCheckReport& report,
                           const map_building::MapCheckOptions& options, double max_range_m) {
  std::cout << std::fixed << std::setprecision(1) << "  " << report.scans << " scans, "
            << report.readings << " readings within " << max_range_m << " m\n  " << report.explained
            << " readings within " << 1000.0 * options.near_m
            << " mm of a wall or pillar: " << 100.0 * report.ExplainedShare()
            << " % explained\n  their distance: median " << 1000.0 * report.median_m
            << " mm, 90 % below " << 1000.0 * report.p90_m << " mm, RMS " << 1000.0 * report.rms_m
            << " mm\n  " << world.Walls().size() << " walls: " << report.walls_disagreeing
            << " disagree (median above " << 1000.0 * options.max_median_m << " mm), "
            << report.walls_rarely_seen << " rarely seen (fewer than " << options.min_readings
            << " readings), " << report.walls_never_seen << " never seen\n";
  PrintDisagreeing(world, report);
}

MapPicture MapCheckPicture(const std::string& title,
                           const std::vector<map_building::PosedScan>& scans,
                           const map_building::MapCheckReport& report,
                           const map_building::MapCheckOptions& options,
                           const std::vector<Eigen::Vector2d>& unexplained) {
  MapPicture picture;
  picture.title = title;
  picture.readings = MapFrameReadings(scans, std::max<size_t>(1, scans.size() / 300));
  const size_t step = std::max<size_t>(1, unexplained.size() / 200000);
  for (size_t i = 0; i < unexplained.size(); i += step) picture.marked.push_back(unexplained[i]);
  picture.wall_colours = WallColours(report, options);
  picture.legend = {{kAgrees, "wall agrees"},
                    {kDisagrees, "wall disagrees"},
                    {kRarelySeen, "rarely seen"},
                    {kNeverSeen, "never seen"},
                    {cv::Scalar(60, 60, 255), "readings no wall explains"}};
  return picture;
}

}  // namespace structloc::cli
