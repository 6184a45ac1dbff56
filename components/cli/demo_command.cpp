// "structloc demo": the main job. Runs launch_xml/demo.launch.xml (simulator
// and localisation as separate processes on a DDS domain, the office scenario
// with odometry errors and people), prints a live line every second (time,
// pose error, features, quality), then a summary of the localised error next
// to the odometry-only error and a PNG like the thesis' Fig. 44.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <thread>

#include "live_verdict.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/config/install_layout.hpp"
#include "structloc/evaluation/live_evaluator.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/rendering/map_canvas.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

int DemoCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"domain", true,
       "DDS domain id, 0..232; keep to 0..101 on Linux (ephemeral ports above; default 0)"},
      {"time-scale", true, "simulated seconds per wall second, 0.01..1000 (default 2)"},
      {"out", true, "PNG to write (default structloc_demo/fig44_office.png in the current folder)"},
  };
  try {
    // Every option is checked here, before anything starts.
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    const int domain = static_cast<int>(cli.IntegerIn("domain", 0, 0, 232));
    const double time_scale = cli.NumberIn("time-scale", 2.0, 0.01, 1000.0);
    const std::string share = config::ShareDirectory();
    const auto scenario =
        simulation_core::LoadScenario(share + "/maps/scenarios/office_people.xml");
    const std::string png = cli.GetOr("out", "structloc_demo/fig44_office.png");
    rendering::MapCanvas::CheckPictureName(png);
    const auto folder = std::filesystem::path(png).parent_path();
    std::filesystem::create_directories(folder);
    // The saved pose beside the picture, in a folder of the user's own: a
    // fixed name in /tmp let another user plant a link there, or block it.
    const std::string state_file =
        (folder.empty() ? std::filesystem::path(".") : folder) / "demo_pose_state.txt";

    dds_common::NodeOptions node_options{
        "demo_observer", domain, share + "/qos/structloc_qos.xml", "structloc_localhost", "", {}};
    dds_common::Node node(node_options);
    evaluation::LiveEvaluator evaluator(node, scenario.initial_pose);
    const auto& p = scenario.initial_pose;
    std::cout
        << "structloc demo: " << scenario.duration_s << " s of simulated driving in the office ("
        << "1 % wheel-radius error, 0.5 deg steering offset, people and boxes), time scale "
        << time_scale << ", DDS domain " << domain << "\n"
        << "  simulator and localisation run as separate processes (launch_xml/demo.launch.xml)"
        << std::endl;
    process::ChildProcess launch(
        inv.bin_dir + "/structloc",
        {"launch", share + "/launch_xml/demo.launch.xml", "domain:=" + std::to_string(domain),
         "time_scale:=" + std::to_string(time_scale),
         "initial_pose:=" + std::to_string(p.x) + " " + std::to_string(p.y) + " " +
             std::to_string(p.theta),
         "state_file:=" + state_file});
    std::optional<int> code;
    while (!(code = launch.WaitExit(std::chrono::seconds(1)))) {
      const auto s = evaluator.Snapshot();
      if (s.position_error_m < 0) {
        std::printf("  t = %5.1f s  waiting for the first pose...\n", s.sim_time_s);
      } else {
        std::printf(
            "  t = %5.1f s  pose error %6.1f mm %6.3f deg  features %2d/%2d  quality %.2f%s\n",
            s.sim_time_s, 1e3 * s.position_error_m, s.heading_error_rad * 180 / geometry::kPi,
            s.matched_features, s.expected_features, s.quality, s.lost ? "  LOST" : "");
      }
      std::fflush(stdout);
    }
    if (*code != 0) {
      std::cerr << "structloc demo: the components failed (exit " << *code << "):\n"
                << launch.CapturedOutput() << std::endl;
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    if (evaluator.EstimateError().matched == 0) {
      std::cerr << "structloc demo: no pose was received:\n"
                << launch.CapturedOutput() << std::endl;
      return 1;
    }
    evaluator.RenderFigure(share + "/maps/office_floor.xml", png,
                           "structloc demo: office, " +
                               std::to_string(static_cast<int>(scenario.duration_s)) +
                               " s, true path / odometry / localised");
    const bool passed = PrintSummaryAndJudge(
        evaluator, node, LiveBar{},
        "is another robot or demo on DDS domain " + std::to_string(domain) + "?");
    std::printf("  picture (true path, odometry, localised estimate): %s\n",
                std::filesystem::weakly_canonical(png).c_str());
    return passed ? 0 : 1;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc demo: " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc demo: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
