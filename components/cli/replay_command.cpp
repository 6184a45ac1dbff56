// "structloc replay --map WORLD.xml --log RUN.clf --initial-pose "X Y THETA"
//  --out TRAJ.tum [--params P.xml] [--truth TRUTH.tum] [--plot OUT.png] [--no-map]":
// runs a recorded CARMEN log through the localisation core, offline.
#include <iostream>

#include "command_line.hpp"
#include "replay.hpp"
#include "strict_number.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

int ReplayCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"map", true, "world model XML (not with --no-map)"},
      {"log", true, "CARMEN log (.clf/.log, or .gz)"},
      {"initial-pose", true, "\"X Y THETA\": map pose of the robot at the first laser line"},
      {"out", true, "TUM trajectory to write (one line per scan)"},
      {"params", true, "localisation parameter file (default: built-in Table 6 defaults)"},
      {"truth", true, "TUM ground truth: adds RMSE, max and heading errors"},
      {"plot", true, "PNG of map, scans, truth, odometry and estimate"},
      {"fixes-out", true, "also write the estimate as fixes.csv (with variances) for calibrate"},
      {"no-map", false, "pass odometry through (parse, filter and time only)"},
  };
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    replay::ReplayOptions o;
    o.no_map = cli.Has("no-map");
    if (!o.no_map) o.map_path = cli.Required("map");
    o.log_path = cli.Required("log");
    o.out_tum = cli.Required("out");
    o.params_path = cli.GetOr("params", "");
    o.truth_path = cli.GetOr("truth", "");
    o.plot_path = cli.GetOr("plot", "");
    o.fixes_path = cli.GetOr("fixes-out", "");
    const std::string pose_text = cli.Required("initial-pose");
    const auto pose = config::ParseNumberList(pose_text, 3);
    if (!pose) {
      throw config::ConfigError(
          "--initial-pose must be exactly three numbers \"X Y THETA\", got '" + pose_text + "'");
    }
    o.initial_pose = {(*pose)[0], (*pose)[1], (*pose)[2]};
    o.progress = [](size_t scans, double) {
      std::cerr << "\rstructloc replay: " << scans << " scans localised" << std::flush;
    };
    const auto report = replay::RunReplay(o);
    std::cerr << "\n";
    std::cout << replay::FormatReport(report) << "wrote " << o.out_tum
              << (o.plot_path.empty() ? "" : " and " + o.plot_path) << "\n";
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc replay: " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc replay: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
