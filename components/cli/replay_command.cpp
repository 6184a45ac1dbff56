// "structloc replay --map WORLD.xml --log RUN.clf [--initial-pose "X Y THETA"]
//  --out TRAJ.tum [--params P.xml] [--truth TRUTH.tum] [--plot OUT.png] [--no-map]
//  [--fixes-out FIXES.csv] [--max-beams N] [--max-lines N] [--global-attempts N]":
// runs a recorded CARMEN log through the localisation core, offline; without
// --initial-pose the robot is first located globally from the first scans.
#include <iostream>
#include <string>

#include "structloc/config/command_line.hpp"
#include "structloc/config/strict_number.hpp"
#include "structloc/replay/replay.hpp"
#include "subcommands.hpp"

namespace structloc::cli {
namespace {

// A limit option: a whole number in [1, most], or `fallback` when not given.
size_t Limit(const config::CommandLine& cli, const std::string& name, size_t fallback,
             long long most) {
  const long long value = cli.Integer(name, static_cast<long long>(fallback));
  if (value < 1 || value > most) {
    throw config::ConfigError("option --" + name + " must be between 1 and " +
                              std::to_string(most));
  }
  return static_cast<size_t>(value);
}

}  // namespace

int ReplayCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"map", true, "world model XML (not with --no-map)"},
      {"log", true, "CARMEN log (.clf/.log, or .gz)"},
      {"initial-pose", true,
       "\"X Y THETA\": map pose of the robot at the first laser line (default: located "
       "globally from the first scans)"},
      {"global-attempts", true,
       "without --initial-pose: scans tried before giving up (default: none, until the log "
       "ends)"},
      {"out", true, "TUM trajectory to write (one line per scan)"},
      {"params", true,
       "localisation parameter file (default: the shipped preset the first scan's geometry "
       "names, printed in the summary; the built-in Table 6 defaults when none does)"},
      {"truth", true,
       "TUM ground truth: adds RMSE, max and heading errors, as they are, after one rigid "
       "alignment (for a map with a frame of its own) and after one that also scales the "
       "estimate (how much of the error is the map's or the truth's scale)"},
      {"plot", true, "PNG of map, scans, truth, odometry and estimate"},
      {"fixes-out", true, "also write the estimate as fixes.csv (with variances) for calibrate"},
      {"no-map", false, "pass odometry through (parse, filter and time only)"},
      {"timings", false,
       "print each stage's time per tracked scan (median, p99, max, mean): prefilter, "
       "expectation, line fits, extraction, solve, whole-scan check, search, and the whole update "
       "as wall and thread CPU time"},
      {"max-beams", true,
       "most beams per laser line; lines with more are malformed (default " +
           std::to_string(log_formats::CarmenLimits{}.max_beams) + ")"},
      {"max-lines", true,
       "most lines read from the log before giving up (default " +
           std::to_string(log_formats::CarmenLimits{}.max_lines) + ")"},
      {"max-walls", true,
       "refuse maps with more walls than this (default " +
           std::to_string(world_model::WorldLimits::kDefaultMaxWalls) + ")"},
  };
  bool progress_shown = false;  // a "\r" progress line that a message must not continue
  const auto end_progress_line = [&progress_shown] {
    if (progress_shown) std::cerr << "\n";
    progress_shown = false;
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
    o.limits.max_beams = Limit(cli, "max-beams", o.limits.max_beams, 10000000);
    o.limits.max_lines = Limit(cli, "max-lines", o.limits.max_lines, 1000000000000);
    o.world_limits.max_walls = Limit(cli, "max-walls", o.world_limits.max_walls, 100000000);
    if (cli.Has("global-attempts"))
      o.global_attempts = Limit(cli, "global-attempts", 1, 1000000000);
    if (cli.Has("initial-pose")) {
      const std::string pose_text = cli.Required("initial-pose");
      const auto pose = config::ParseNumberList(pose_text, 3);
      if (!pose) {
        throw config::ConfigError(
            "--initial-pose must be exactly three numbers \"X Y THETA\", got '" + pose_text + "'");
      }
      o.initial_pose = geometry::Pose2D{(*pose)[0], (*pose)[1], (*pose)[2]};
    }
    o.progress = [&progress_shown](size_t scans, double) {
      std::cerr << "\rstructloc replay: " << scans << " scans localised" << std::flush;
      progress_shown = true;
    };
    const auto report = replay::RunReplay(o);
    end_progress_line();
    std::cout << replay::FormatReport(report);
    if (cli.Has("timings")) std::cout << replay::FormatStageTimes(report);
    std::cout << "wrote " << o.out_tum << (o.plot_path.empty() ? "" : " and " + o.plot_path)
              << "\n";
    return 0;
  } catch (const config::ConfigError& e) {
    end_progress_line();
    std::cerr << "structloc replay: " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  } catch (const std::exception& e) {
    end_progress_line();
    std::cerr << "structloc replay: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
