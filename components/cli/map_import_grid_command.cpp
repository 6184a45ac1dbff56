// "structloc map import --grid MAP.yaml --out WORLD.xml [--plot P.png]": walls,
// corners and pillars from a ROS map_server occupancy grid (what slam_toolbox,
// gmapping, Cartographer or Nav2's map_saver wrote), so that a building
// already mapped for ROS needs no new survey. The world file and the picture
// replace existing ones only when complete.
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "map_action.hpp"
#include "map_subcommands.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/config/output_file.hpp"
#include "structloc/map_building/grid_vectoriser.hpp"
#include "structloc/map_formats/grid_map_file.hpp"
#include "structloc/rendering/map_canvas.hpp"
#include "structloc/world_model/world_model_xml.hpp"

namespace structloc::cli {
namespace {

void DrawPlot(const map_building::OccupancyGrid& grid, int occupied_min_value,
              const world_model::WorldModel& world, const std::string& title,
              config::OutputFile& file) {
  std::vector<Eigen::Vector2d> occupied;
  for (int row = 0; row < grid.height; ++row)
    for (int column = 0; column < grid.width; ++column)
      if (grid.At(column, row) >= occupied_min_value)
        occupied.push_back(grid.CellCentre(column, row));
  Eigen::Vector4d bounds = world.Bounds();
  for (const auto& p : occupied) {
    bounds[0] = std::min(bounds[0], p.x());
    bounds[1] = std::min(bounds[1], p.y());
    bounds[2] = std::max(bounds[2], p.x());
    bounds[3] = std::max(bounds[3], p.y());
  }
  rendering::MapCanvas canvas(bounds, 40.0);
  const cv::Scalar cell_colour(0, 170, 255);
  canvas.DrawPoints(occupied, cell_colour, 1);
  canvas.DrawWorld(world);
  canvas.DrawLegend({{cell_colour, "occupied cells of the grid"},
                     {rendering::colours::kWall, "imported walls, pillars, corners"}});
  canvas.DrawTitle(title);
  canvas.WriteTo(file);
}

// The command's options, with the vectoriser's defaults in their help.
std::vector<config::OptionSpec> Specs(const map_building::GridVectoriseOptions& defaults) {
  auto number = [](double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  return {
      {"grid", true, "map_server YAML (with its PGM or PNG image) to import"},
      {"out", true, "world XML to write"},
      {"plot", true, "PNG: the occupied cells with the imported map over them"},
      {"name", true, "name of the world (default: the YAML's file name without extension)"},
      {"min-wall-length", true,
       "shortest wall piece kept, m (default " + number(defaults.min_wall_length_m) + ")"},
      {"max-gap", true,
       "a wider gap in a wall's cells is a door, m (default " + number(defaults.max_gap_m) + ")"},
      {"min-wall-blob", true,
       "blobs of occupied cells smaller than this (bounding box) are furniture, not walls, m "
       "(default " +
           number(defaults.min_wall_blob_size_m) + ")"},
      {"join-gap", true,
       "blobs this close (m of empty cells between them, rounded down to whole cells, at most "
       "64 cells) are "
       "judged together against --min-wall-blob, and are no specks: a wall seen by few scans is "
       "dotted in a ray-cast grid; furniture this near a wall goes with the wall; 0 judges each "
       "blob alone, m in [0, 1] (default " +
           number(defaults.max_join_gap_m) + ")"},
      {"max-pillar-radius", true,
       "largest pillar radius, m (default " + number(defaults.max_pillar_radius_m) + ")"},
      {"ignore-unknown-keys", false,
       "ignore YAML keys map_server does not read (as ROS does) instead of refusing them"},
      {"max-cells", true,
       "larger images are refused before they are decoded, cells (default " +
           std::to_string(map_formats::GridMapReadOptions::kDefaultMaxCells) + ")"},
      {"max-face-cells", true,
       "grids with more occupied cells next to open space are refused (default " +
           std::to_string(defaults.max_face_cells) + ")"},
      {"max-blobs", true,
       "grids with more blobs of occupied cells are refused (default " +
           std::to_string(defaults.max_blobs) + ")"},
      {"max-refit-work", true,
       "refitting the wall proposals may gather at most this many face cells, each counted "
       "every time (default " +
           std::to_string(defaults.max_refit_work) +
           "; the real recordings' grids need under 300000)"},
  };
}

// A work limit of the command line: a count from 1 to 1e12.
size_t Limit(const config::CommandLine& cli, const char* option, size_t fallback) {
  return static_cast<size_t>(
      cli.IntegerIn(option, static_cast<long long>(fallback), 1, 1000000000000LL));
}

// The vectoriser's options from the command line (bounded as the help says).
map_building::GridVectoriseOptions VectoriseOptions(
    const config::CommandLine& cli, const map_building::GridVectoriseOptions& defaults) {
  map_building::GridVectoriseOptions options;
  options.min_wall_length_m =
      cli.NumberIn("min-wall-length", defaults.min_wall_length_m, 1e-3, 1e3);
  options.max_gap_m = cli.NumberIn("max-gap", defaults.max_gap_m, 1e-3, 1e3);
  options.min_wall_blob_size_m =
      cli.NumberIn("min-wall-blob", defaults.min_wall_blob_size_m, 0.0, 1e3);
  options.max_join_gap_m = cli.NumberIn("join-gap", defaults.max_join_gap_m, 0.0, 1.0);
  options.max_pillar_radius_m = cli.NumberIn("max-pillar-radius", defaults.max_pillar_radius_m,
                                             defaults.min_pillar_radius_m, 1e3);
  options.max_face_cells = Limit(cli, "max-face-cells", defaults.max_face_cells);
  options.max_blobs = Limit(cli, "max-blobs", defaults.max_blobs);
  options.max_refit_work = Limit(cli, "max-refit-work", defaults.max_refit_work);
  return options;
}

// What was read, made and left out, and where it was written.
void PrintSummary(const std::string& grid_path, const map_building::OccupancyGrid& grid,
                  const map_building::GridVectorisation& result,
                  const map_building::GridVectoriseOptions& options,
                  const world_model::WorldModel& world, const std::string& out_path,
                  const std::optional<std::string>& plot_path) {
  std::cout << "structloc map import: " << grid_path << ": " << result.cells << " cells read ("
            << grid.width << " x " << grid.height << " of " << grid.resolution_m << " m), "
            << result.occupied_cells << " occupied, " << result.face_cells
            << " facing free space in " << result.wall_blobs << " wall blobs\n"
            << "  " << world.Walls().size() << " walls, " << world.Corners().size() << " corners ("
            << result.corners_joined << " wall ends joined; " << result.short_after_joining
            << " walls shorter than " << options.min_wall_length_m << " m after that, dropped), "
            << world.Cylinders().size() << " pillars\n"
            << "  left out: " << result.blobs_left_out
            << " blobs too small for a wall, alone or with the blobs near them, and not round "
               "(furniture), "
            << result.specks_left_out << " specks of at most " << options.max_speck_cells
            << " cells (noise)\n"
            << "  wrote " << out_path;
  if (plot_path) std::cout << " and " << *plot_path;
  std::cout << "\n";
}

}  // namespace

int MapImportGridCommand(const Invocation& inv) {
  const map_building::GridVectoriseOptions defaults;
  return RunMapAction(inv, "import", Specs(defaults), [&](const config::CommandLine& cli) {
    const std::string grid_path = cli.Required("grid");
    const std::string out_path = cli.Required("out");
    const auto plot_path = cli.Get("plot");
    if (plot_path) rendering::MapCanvas::CheckPictureName(*plot_path);
    map_building::GridVectoriseOptions options = VectoriseOptions(cli, defaults);
    map_formats::GridMapReadOptions read;
    read.ignore_unknown_keys = cli.Has("ignore-unknown-keys");
    read.max_cells = Limit(cli, "max-cells", read.max_cells);
    const std::string name = cli.GetOr("name", std::filesystem::path(grid_path).stem().string());

    map_formats::GridMapSource source;
    const auto grid = map_formats::LoadGridMap(grid_path, read, &source);
    const map_formats::GridMapMode mode = source.mode;
    // Both outputs are refused before any work when they would replace an
    // input: the YAML or the image it names.
    const std::vector<std::string> inputs{grid_path, source.image_path};
    config::OutputFile out(out_path, inputs);
    std::optional<config::OutputFile> plot;
    if (plot_path) {
      std::vector<std::string> plot_inputs = inputs;
      plot_inputs.push_back(out_path);
      plot.emplace(*plot_path, plot_inputs);
    }
    // Trinary and scale grids come with the YAML's thresholds applied: a value
    // below 100 is below occupied_thresh (scale's 0..99 only grade the cells
    // in between). Raw grids hold probabilities in percent, judged by the
    // vectoriser's map_saver thresholds.
    if (mode != map_formats::GridMapMode::kRaw) {
      options.occupied_min_value = map_building::OccupancyGrid::kOccupied;
      options.free_max_value = map_building::OccupancyGrid::kFree;
    }
    map_building::GridVectorisation result;
    try {
      result = map_building::VectoriseGrid(grid, options);
    } catch (const std::invalid_argument& e) {
      throw config::ConfigError(grid_path + ": " + e.what());
    }
    if (result.walls.empty() && result.pillars.empty())
      throw std::runtime_error(grid_path + ": found no wall or pillar in " +
                               std::to_string(result.occupied_cells) +
                               " occupied cells (see --min-wall-length and --min-wall-blob)");
    const auto world = map_building::MakeWorld(name, result.walls, result.pillars);

    std::ostringstream made;
    made << "made by structloc map import --grid " << grid_path << " (" << grid.width << " x "
         << grid.height << " cells of " << grid.resolution_m << " m), min wall length "
         << options.min_wall_length_m << " m, max gap " << options.max_gap_m << " m, min wall blob "
         << options.min_wall_blob_size_m << " m, join gap " << options.max_join_gap_m
         << " m, max pillar radius " << options.max_pillar_radius_m << " m";
    world_model::WriteWorldModel(world, {made.str()}, out.Stream());
    if (plot) {
      DrawPlot(grid, options.occupied_min_value, world,
               name + ": " + std::to_string(world.Walls().size()) + " walls, " +
                   std::to_string(world.Cylinders().size()) + " pillars from " + grid_path,
               *plot);
      plot->Flush();
    }
    out.Flush();
    out.Commit();
    if (plot) plot->Commit();
    PrintSummary(grid_path, grid, result, options, world, out_path, plot_path);
    return 0;
  });
}

}  // namespace structloc::cli
