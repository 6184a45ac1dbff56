// "structloc map check --map WORLD.xml --log LOG [--plot P.png]": how well a map
// agrees with a recording whose scan poses are corrected: the distance of the
// readings that hit each wall, how often each is seen, walls never seen, and the
// share of readings no wall explains, so that a user can trust or fix a map. The
// picture marks the disagreeing walls. With --fit-poses, also how far each
// scan's recorded pose lies from the pose at which the map explains it best
// (where a reference trajectory and the map disagree).
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <optional>

#include "map_action.hpp"
#include "map_check_findings.hpp"
#include "map_picture.hpp"
#include "map_subcommands.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/config/output_file.hpp"
#include "structloc/map_building/map_check.hpp"
#include "structloc/map_building/scan_pose_fit.hpp"
#include "structloc/rendering/map_canvas.hpp"
#include "structloc/world_model/world_model_xml.hpp"

namespace structloc::cli {
namespace {

// The columns of --fit-poses-out, one row per scan.
constexpr const char* kPoseFitColumns =
    "scan,fitted,converged,iterations,readings,dx_m,dy_m,dtheta_rad";

// The summary of the scans' best-fit offsets, the ten farthest, and the CSV
// (written through `csv` when given; committed by the caller).
void ReportPoseFits(const std::vector<map_building::ScanPoseFit>& fits, config::OutputFile* csv) {
  const auto summary = map_building::SummarisePoseFits(fits, 10);
  constexpr double kDeg = 180.0 / geometry::kPi;
  std::cout << std::fixed << "  scan poses fitted to the map alone: " << summary.converged << " of "
            << summary.scans << " scans (" << summary.scans - summary.fitted
            << " with too few readings near the map, " << summary.fitted - summary.converged
            << " not converged)\n";
  if (summary.converged > 0) {
    std::cout << std::setprecision(1) << "    offset from the recorded pose: position median "
              << 1000.0 * summary.median_shift_m << " mm, 90 % below "
              << 1000.0 * summary.p90_shift_m << " mm, max " << 1000.0 * summary.max_shift_m
              << " mm;" << std::setprecision(2) << " heading median "
              << kDeg * summary.median_turn_rad << " deg, 90 % below "
              << kDeg * summary.p90_turn_rad << " deg, max " << kDeg * summary.max_turn_rad
              << " deg\n    farthest in position (scan: x, y mm, heading deg):";
    for (size_t k = 0; k < summary.farthest.size(); ++k) {
      const auto& f = fits[summary.farthest[k]];
      std::cout << (k % 3 == 0 ? "\n     " : "") << " " << f.index << ": " << std::showpos
                << std::setprecision(1) << 1000.0 * f.offset.x << ", " << 1000.0 * f.offset.y
                << ", " << std::setprecision(2) << kDeg * f.offset.theta << std::noshowpos << ";";
    }
    std::cout << "\n";
  }
  if (csv == nullptr) return;
  auto& out = csv->Stream();
  out << kPoseFitColumns << "\n" << std::setprecision(6);
  for (const auto& f : fits) {
    out << f.index << "," << f.fitted << "," << f.converged << "," << f.iterations << ","
        << f.readings << "," << f.offset.x << "," << f.offset.y << "," << f.offset.theta << "\n";
  }
  std::cout << "  pose fits: " << csv->Path() << "\n";
}

}  // namespace

int MapCheckCommand(const Invocation& inv) {
  const map_building::MapCheckOptions defaults;
  const std::vector<config::OptionSpec> specs = {
      {"map", true, "world XML to check"},
      {"log", true, "CARMEN log whose scan poses are corrected (e.g. by SLAM), .gz or plain"},
      {"scans", true,
       "use only the scans FIRST:LAST of the log (numbers from 0, LAST not included; default: "
       "all), e.g. to build from one part and check on another"},
      {"plot", true, "PNG of the map over the readings, disagreeing walls marked"},
      {"near", true, "a reading this close to a wall or pillar hits it, m (default 0.1)"},
      {"max-median", true, "walls whose readings lie farther (median) disagree, m (default 0.03)"},
      {"max-range", true, "readings farther than this are left out, m (default 20)"},
      {"fit-poses", false,
       "also fit each scan alone to the map from its recorded pose (readings within --near, at "
       "least 30, up to 30 Gauss-Newton steps) and report how far the best fit lies (where the "
       "recorded poses and the map disagree)"},
      {"fit-poses-out", true,
       std::string("CSV of each scan's fit (") + kPoseFitColumns + "); implies --fit-poses"},
  };
  return RunMapAction(inv, "check", specs, [&](const config::CommandLine& cli) {
    const std::string map_path = cli.Required("map");
    const std::string log_path = cli.Required("log");
    const std::vector<std::string> inputs{map_path, log_path};
    const std::string plot_path = cli.GetOr("plot", "");
    if (!plot_path.empty()) rendering::MapCanvas::CheckPictureName(plot_path);
    map_building::MapCheckOptions options;
    options.near_m = cli.NumberIn("near", defaults.near_m, 1e-3, 10.0);
    options.max_median_m = cli.NumberIn("max-median", defaults.max_median_m, 1e-4, 10.0);
    map_building::PosedScanOptions scan_options;
    scan_options.max_range_m =
        cli.NumberIn("max-range", scan_options.max_range_m, scan_options.min_range_m + 0.01, 1e3);
    // The outputs first: refused before any work when they would replace an
    // input, and committed together at the end.
    std::optional<config::OutputFile> csv, plot;
    if (cli.Has("fit-poses-out")) csv.emplace(cli.Required("fit-poses-out"), inputs);
    if (!plot_path.empty()) {
      auto plot_inputs = inputs;
      if (csv) plot_inputs.push_back(csv->Path());
      plot.emplace(plot_path, plot_inputs);
    }
    const auto world = world_model::LoadWorldModel(map_path);
    const auto range = map_building::ParseScanRange(cli.GetOr("scans", ":"));
    auto log = map_building::ReadPosedScans(log_path, scan_options);
    map_building::KeepScans(log, range.first, range.second);
    std::cerr << log_formats::MalformedLinesText(log.reader, log_path);
    std::vector<Eigen::Vector2d> unexplained;
    const auto report = map_building::CheckMap(world, log.scans, options, &unexplained);
    std::cout << "structloc map check: " << map_path << " against " << log_path << "\n";
    PrintMapCheckFindings(world, report, options, scan_options.max_range_m);
    if (cli.Has("fit-poses") || cli.Has("fit-poses-out")) {
      map_building::ScanPoseFitOptions fit_options;
      fit_options.near_m = options.near_m;
      ReportPoseFits(map_building::FitScanPoses(world, log.scans, fit_options),
                     csv ? &*csv : nullptr);
    }
    if (plot) {
      const auto picture =
          MapCheckPicture("map check: " + map_path, log.scans, report, options, unexplained);
      WriteMapPicture(*plot, world, picture);
      std::cout << "  picture: " << plot_path << "\n";
    }
    for (auto* file : {csv ? &*csv : nullptr, plot ? &*plot : nullptr}) {
      if (file != nullptr) file->Flush();
    }
    if (csv) csv->Commit();
    if (plot) plot->Commit();
    return 0;
  });
}

}  // namespace structloc::cli
