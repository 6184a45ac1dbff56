// "structloc map import --dxf DRAWING.dxf --layers L1,L2 --out WORLD.xml
//  [--units mm|cm|m|in|ft] [--plot P.png]": a world map from the chosen layers
// of a CAD drawing (walls from lines and polylines, pillars from circles,
// corners from points), with a summary of what was read, used and skipped.
// Every input is read and checked before the outputs are written; the map and
// the picture replace existing files only when both were written.
#include <algorithm>
#include <iostream>
#include <optional>
#include <sstream>

#include "file_names.hpp"
#include "map_action.hpp"
#include "map_subcommands.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/config/output_file.hpp"
#include "structloc/map_building/dxf_import.hpp"
#include "structloc/map_formats/dxf_drawing.hpp"
#include "structloc/rendering/map_canvas.hpp"
#include "structloc/world_model/world_model_xml.hpp"

namespace structloc::cli {
namespace {

constexpr const char* kName = "structloc map import";

std::vector<std::string> SplitLayers(const std::string& text) {
  std::vector<std::string> layers;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto first = item.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    layers.push_back(item.substr(first, item.find_last_not_of(" \t") - first + 1));
  }
  if (layers.empty())
    throw config::ConfigError("--layers names no layer: give e.g. --layers WALLS,PILLARS");
  return layers;
}

std::vector<std::string> CommentLines(const std::string& dxf_path,
                                      const map_building::DxfImportReport& report) {
  std::vector<std::string> lines = {"Imported from the CAD drawing " + dxf_path +
                                    " by structloc map import."};
  std::istringstream summary(map_building::FormatImportReport(report));
  for (std::string line; std::getline(summary, line);) lines.push_back(line);
  return lines;
}

Eigen::Vector4d Bounds(const world_model::WorldModel& world, const world_model::Scene& extra) {
  Eigen::Vector4d b = world.Bounds();
  const auto grow = [&b](const Eigen::Vector2d& p, double r) {
    b[0] = std::min(b[0], p.x() - r);
    b[1] = std::min(b[1], p.y() - r);
    b[2] = std::max(b[2], p.x() + r);
    b[3] = std::max(b[3], p.y() + r);
  };
  for (const auto& s : extra.segments) {
    grow(s.a, 0.0);
    grow(s.b, 0.0);
  }
  for (const auto& c : extra.circles) grow(c.centre, c.radius);
  return b;
}

}  // namespace

int MapImportDxfCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"dxf", true, "CAD drawing (ASCII DXF) to import"},
      {"layers", true,
       "comma-separated layers to import, matched case-insensitively (e.g. WALLS,PILLARS)"},
      {"out", true, "world model XML to write"},
      {"units", true,
       "unit of the drawing's coordinates: mm, cm, m, in or ft (default: the drawing's "
       "$INSUNITS; millimetres, with a warning, when it has none)"},
      {"plot", true, "PNG of the imported map over the layers left out (drawn lighter)"},
  };
  return RunMapAction(inv, "import", specs, [&](const config::CommandLine& cli) {
    const std::string dxf_path = cli.Required("dxf");
    const std::string out_path = cli.Required("out");
    const std::string plot_path = cli.GetOr("plot", "");
    if (!plot_path.empty()) rendering::MapCanvas::CheckPictureName(plot_path);
    map_building::DxfImportOptions options;
    options.layers = SplitLayers(cli.Required("layers"));
    if (cli.Has("units")) options.units = map_building::ParseLengthUnit(cli.Required("units"));
    options.world_name = Stem(dxf_path, "imported");

    const auto drawing = map_formats::ReadDxfDrawing(dxf_path);
    const auto imported = map_building::ImportDrawing(drawing, options);
    const auto& report = imported.report;
    if (report.unit_assumed) {
      std::cerr << kName << ": warning: " << dxf_path << " does not say its unit; assumed "
                << report.unit.name << " (give --units mm|cm|m|in|ft if that is wrong)\n";
    }

    config::OutputFile out(out_path, {dxf_path});
    world_model::WriteWorldModel(imported.world, CommentLines(dxf_path, report), out.Stream());
    std::optional<config::OutputFile> plot;
    bool scaled_down = false;
    if (!plot_path.empty()) {
      plot.emplace(plot_path, std::vector<std::string>{dxf_path, out_path});
      rendering::MapCanvas canvas(Bounds(imported.world, imported.left_out), 40.0);
      const cv::Scalar left_out_colour(200, 200, 200);
      canvas.DrawObstacles(imported.left_out, left_out_colour);
      canvas.DrawWorld(imported.world);
      canvas.DrawLegend({{rendering::colours::kWall, "imported: walls, pillars, corners"},
                         {left_out_colour, "layers left out"}});
      std::string layers;
      for (const auto& [layer, kinds] : report.layers)
        layers += (layers.empty() ? "" : ", ") + layer;
      canvas.DrawTitle(FileName(dxf_path) + ", layers " + layers + ": " +
                       std::to_string(report.walls) + " walls, " + std::to_string(report.pillars) +
                       " pillars");
      canvas.WriteTo(*plot);
      plot->Flush();
      scaled_down = canvas.ScaledDown();
    }
    out.Flush();
    out.Commit();
    if (plot) plot->Commit();
    std::cout << kName << ": " << dxf_path << "\n" << map_building::FormatImportReport(report);
    std::cout << "wrote " << out_path;
    if (plot) std::cout << " and " << plot_path << (scaled_down ? " (scaled down)" : "");
    std::cout << "\n";
    return 0;
  });
}

}  // namespace structloc::cli
