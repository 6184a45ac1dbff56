// "structloc render --scenario S.xml --out PICTURE.png [--time T]": draws the
// scenario (walls, pillars, obstacles, people, planned path) and the scan the
// robot takes at time T, as a PNG. The picture name is checked before any
// work, and an existing picture is replaced only when the new one is complete.
#include <iostream>

#include "structloc/config/command_line.hpp"
#include "structloc/config/output_file.hpp"
#include "structloc/rendering/map_canvas.hpp"
#include "structloc/simulation_core/simulation.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

int RenderCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"scenario", true, "scenario XML file"},
      {"out", true, "PNG to write"},
      {"time", true, "simulation time of the scan to draw, s (default 0: the first scan)"},
  };
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    const std::string out_path = cli.Required("out");
    rendering::MapCanvas::CheckPictureName(out_path);
    const std::string scenario_path = cli.Required("scenario");
    const double at = cli.Number("time", 0.0);
    const auto scenario = simulation_core::LoadScenario(scenario_path);
    config::OutputFile out(out_path, {scenario_path});
    simulation_core::Simulation sim(scenario);
    std::optional<simulation_core::SimScan> scan;
    std::vector<Eigen::Vector2d> driven{scenario.initial_pose.Translation()};
    while (!sim.Finished()) {
      driven.push_back(sim.Step().truth.Translation());
      auto s = sim.TakeScan();
      if (s && s->stamp >= at) {
        scan = std::move(s);
        break;
      }
    }
    if (!scan)
      throw std::runtime_error("the scenario ends before a scan at t = " + std::to_string(at));
    rendering::MapCanvas canvas(scenario.world->Bounds(), 40.0);
    canvas.DrawWorld(*scenario.world);
    canvas.DrawObstacles(scenario.obstacles, rendering::colours::kObstacle);
    world_model::Scene people;
    people.circles = sim.People();
    canvas.DrawObstacles(people, rendering::colours::kPerson);
    std::vector<Eigen::Vector2d> planned{scenario.initial_pose.Translation()};
    planned.insert(planned.end(), scenario.path.waypoints.begin(), scenario.path.waypoints.end());
    canvas.DrawPath(planned, rendering::colours::kPlanned, 1);
    canvas.DrawPath(driven, rendering::colours::kTruth, 2);
    // The scan's points, each from the sensor pose at its own time (no de-skew needed to draw).
    std::vector<Eigen::Vector2d> points;
    const geometry::Pose2D laser = geometry::Compose(scan->truth, scenario.laser.mount);
    for (size_t i = 0; i < scan->ranges.size(); ++i) {
      const double r = scan->ranges[i];
      if (!std::isfinite(r) || r < scan->range_min || r > scan->range_max) continue;
      const double a = scan->angle_min + static_cast<double>(i) * scan->angle_increment;
      points.push_back(laser.Apply({r * std::cos(a), r * std::sin(a)}));
    }
    canvas.DrawPoints(points, rendering::colours::kScan, 2);
    canvas.DrawPose(scan->truth, rendering::colours::kTruth);
    canvas.DrawLegend({{rendering::colours::kWall, "world model: walls, pillars, corners"},
                       {rendering::colours::kObstacle, "unmodelled boxes and pillars"},
                       {rendering::colours::kPerson, "people"},
                       {rendering::colours::kPlanned, "planned path"},
                       {rendering::colours::kTruth, "driven so far / robot"},
                       {rendering::colours::kScan, "laser scan"}});
    canvas.DrawTitle(scenario.name + ": scan at t = " + std::to_string(scan->stamp).substr(0, 5) +
                     " s, " + std::to_string(points.size()) + " returns");
    canvas.WriteTo(out);
    out.Commit();
    std::cout << "structloc render: wrote " << out_path;
    if (canvas.ScaledDown()) {
      std::cout << " (scaled down to " << canvas.PixelsPerMetre()
                << " pixels per metre to stay within " << rendering::MapCanvas::kDefaultMaxSidePx
                << " pixels)";
    }
    std::cout << "\n";
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc render: " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc render: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
