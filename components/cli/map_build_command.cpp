// "structloc map build --log LOG --out WORLD.xml [--params P.xml] [--plot P.png]":
// walls, corners and pillars from a recording whose scan poses are corrected
// (thesis 6.5.5, map building), written as a world file; every wall's support
// (points, scans) and residual RMS is listed.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <optional>

#include "file_names.hpp"
#include "map_action.hpp"
#include "map_picture.hpp"
#include "map_subcommands.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/config/output_file.hpp"
#include "structloc/map_building/map_builder.hpp"
#include "structloc/rendering/map_canvas.hpp"
#include "structloc/world_model/world_model_xml.hpp"

namespace structloc::cli {
namespace {

void PrintSupport(const map_building::MapBuildResult& result) {
  std::cout << "  wall  length_m  points  scans  rms_mm\n" << std::fixed;
  for (size_t i = 0; i < result.walls.size(); ++i) {
    const auto& w = result.walls[i];
    std::cout << std::setw(6) << i + 1 << std::setw(10) << std::setprecision(2) << w.Length()
              << std::setw(8) << w.points << std::setw(7) << w.sources << std::setw(8)
              << std::setprecision(1) << 1000.0 * w.rms_m << "\n";
  }
}

}  // namespace

int MapBuildCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"log", true, "CARMEN log whose scan poses are corrected (e.g. by SLAM), .gz or plain"},
      {"scans", true,
       "use only the scans FIRST:LAST of the log (numbers from 0, LAST not included; default: "
       "all), e.g. to build from one part and check on another"},
      {"out", true, "world XML to write"},
      {"params", true,
       "<map_build_params> file (default: the built-in defaults, for a 180 deg "
       "SICK-like laser; `structloc params --map-build` lists them)"},
      {"plot", true, "PNG of the map over the recording's readings"},
      {"name", true, "the world's name (default: the log's file name)"},
      {"quiet", false, "leave out the table of every wall's support"},
  };
  return RunMapAction(inv, "build", specs, [&](const config::CommandLine& cli) {
    const std::string log_path = cli.Required("log");
    const std::string out_path = cli.Required("out");
    const std::string plot_path = cli.GetOr("plot", "");
    if (!plot_path.empty()) rendering::MapCanvas::CheckPictureName(plot_path);
    const std::string params_path = cli.GetOr("params", "");
    const auto options = params_path.empty() ? map_building::MapBuildOptions{}
                                             : map_building::LoadMapBuildOptions(params_path);
    std::vector<std::string> inputs{log_path};
    if (!params_path.empty()) inputs.push_back(params_path);
    config::OutputFile out(out_path, inputs);
    std::optional<config::OutputFile> plot;
    if (!plot_path.empty()) {
      inputs.push_back(out_path);
      plot.emplace(plot_path, inputs);
    }

    const auto range = map_building::ParseScanRange(cli.GetOr("scans", ":"));
    auto log = map_building::ReadPosedScans(log_path, options.scans);
    map_building::KeepScans(log, range.first, range.second);
    const auto result = map_building::BuildMap(log.scans, options);
    if (result.walls.empty() && result.pillars.empty()) {
      throw std::runtime_error(log_path + ": no wall or pillar met the options' bars (" +
                               std::to_string(result.wall_report.segments) +
                               " scan segments); see structloc params --map-build");
    }
    const auto world = map_building::MakeWorld(cli.GetOr("name", Stem(log_path, "built")),
                                               result.walls, result.pillars);
    const auto& r = result.wall_report;
    world_model::WriteWorldModel(
        world,
        {"Built by `structloc map build` from " + FileName(log_path) +
             (params_path.empty() ? " with the default options"
                                  : " with " + FileName(params_path)) +
             ":",
         std::to_string(log.scans.size()) + " scans, " + std::to_string(r.segments) +
             " scan segments merged into " + std::to_string(world.Walls().size()) + " walls, " +
             std::to_string(world.Cylinders().size()) + " pillars."},
        out.Stream());
    if (plot) {
      MapPicture picture;
      picture.title = "map build: " + Stem(log_path, "built");
      picture.readings = MapFrameReadings(log.scans, std::max<size_t>(1, log.scans.size() / 500));
      picture.legend = {{rendering::colours::kWall, "walls and pillars built"},
                        {cv::Scalar(200, 200, 200), "readings"}};
      WriteMapPicture(*plot, world, picture);
      plot->Flush();
    }
    // Both on disk before either replaces a file: a failed picture leaves the
    // world as it was.
    out.Flush();
    out.Commit();
    if (plot) plot->Commit();

    std::cerr << log_formats::MalformedLinesText(log.reader, log_path);
    std::cout << "structloc map build: " << log.scans.size() << " scans (" << log.readings
              << " readings, " << log.out_of_range << " out of range";
    if (log.reader.malformed > 0) std::cout << ", " << log.reader.malformed << " malformed lines";
    std::cout << ")\n"
              << map_building::DeskewText(log) << "  " << r.segments << " scan segments -> "
              << r.candidates << " wall candidates (" << r.merged << " merged) -> " << r.pieces
              << " pieces split at gaps\n  dropped: " << r.too_few_scans << " seen from fewer than "
              << options.walls.min_scans << " scans, " << r.too_few_points << " with fewer than "
              << options.walls.min_points << " points, " << r.too_rough << " rougher than "
              << 1000.0 * options.walls.max_rms_m << " mm RMS, " << r.too_short << " shorter than "
              << options.walls.min_length_m << " m, " << result.walls_on_pillars << " on a pillar, "
              << result.shadow_walls << " shadows of longer walls\n  " << world.Walls().size()
              << " walls, " << result.corners_joined << " corners joined (then "
              << result.short_after_joining << " walls shorter than " << options.walls.min_length_m
              << " m dropped; " << world.Corners().size() << " corners derived), "
              << world.Cylinders().size() << " pillars (" << result.pillar_report.sightings
              << " arc sightings, " << result.pillar_report.too_few_scans << " seen too rarely, "
              << result.pillar_report.seen_through << " seen through: people who moved, "
              << result.pillar_report.merged << " built twice and merged)\n  wrote " << out_path
              << "\n";
    if (!cli.Has("quiet")) PrintSupport(result);
    if (plot) std::cout << "  picture: " << plot_path << "\n";
    return 0;
  });
}

}  // namespace structloc::cli
