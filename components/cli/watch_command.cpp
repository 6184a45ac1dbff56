// "structloc watch": the checker of a deployed run. Joins the DDS domain like
// any client (its own participant, possibly on another host, in a container
// or a network namespace), follows the simulator's ground truth and the
// localisation's poses until the simulated run ends (ground truth silent for
// --quiet-s), prints the summary and exits 0 only when the run met the demo's
// accuracy bar: what the container and multi-host tests assert.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <thread>

#include "live_verdict.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/dds_common/component_runtime.hpp"
#include "structloc/log_formats/recording_writers.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

int WatchCommand(const Invocation& inv) {
  std::vector<config::OptionSpec> specs = dds_common::StandardOptions();
  specs.push_back({"scenario", true,
                   "the simulator's scenario, for odometry's start (default: "
                   "maps/scenarios/office_people.xml in structloc's data folder)"});
  specs.push_back({"timeout-s", true, "give up after this long, 1..86400 (default 600)"});
  specs.push_back(
      {"quiet-s", true,
       "the run has ended when ground truth has been silent this long, 0.5..600 (default 3)"});
  specs.push_back({"max-rmse-m", true, "bar: position RMSE (default 0.010)"});
  specs.push_back({"max-error-m", true, "bar: largest position error (default 0.030)"});
  specs.push_back({"min-poses", true, "bar: poses matched to ground truth (default 500)"});
  specs.push_back({"max-pose-age-ms", true,
                   "bar: 95th percentile of the newest pose's age while poses flow, 1..60000 ms "
                   "(default: printed, not judged)"});
  specs.push_back({"estimate-out", true,
                   "write the poses received to this TUM file (stamp x y z qx qy qz qw)"});
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    const auto timeout = std::chrono::duration<double>(cli.NumberIn("timeout-s", 600, 1, 86400));
    const auto quiet = std::chrono::duration<double>(cli.NumberIn("quiet-s", 3, 0.5, 600));
    LiveBar bar;
    bar.max_rmse_m = cli.NumberIn("max-rmse-m", bar.max_rmse_m, 1e-6, 1e3);
    bar.max_error_m = cli.NumberIn("max-error-m", bar.max_error_m, 1e-6, 1e3);
    bar.min_poses = static_cast<size_t>(cli.IntegerIn("min-poses", 500, 1, 100000000));
    if (cli.Has("max-pose-age-ms")) {
      bar.max_pose_age_p95_s = 1e-3 * cli.NumberIn("max-pose-age-ms", 200, 1, 60000);
    }
    const std::string estimate_out = cli.GetOr("estimate-out", "");
    const auto scenario =
        simulation_core::LoadScenario(cli.PathOr("scenario", "maps/scenarios/office_people.xml"));
    const auto options = dds_common::NodeOptionsFrom(cli, "watch", "operator");
    dds_common::Node node(options);
    evaluation::LiveEvaluator evaluator(node, scenario.initial_pose);
    std::printf(
        "structloc watch: DDS domain %d, profile %s, waiting for the run (at most %.0f s)\n",
        options.domain_id, options.participant_profile.c_str(), timeout.count());
    std::fflush(stdout);
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto last_change = start;
    size_t truth_seen = 0;
    while (true) {
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
      const size_t truth = evaluator.Truth().size();
      const auto now = Clock::now();
      if (truth != truth_seen) {
        if (truth_seen == 0) {
          std::printf("  ground truth arriving\n");
          std::fflush(stdout);  // scripts wait for this line (tests/security)
        }
        truth_seen = truth;
        last_change = now;
      } else if (truth_seen > 0 && now - last_change > quiet) {
        break;
      }
      if (now - start > timeout) {
        std::printf("  FAILED: %s after %.0f s\n",
                    truth_seen == 0 ? "no ground truth (is the simulator on this domain?)"
                                    : "the run had not ended",
                    timeout.count());
        return 1;
      }
    }
    if (!estimate_out.empty()) {
      log_formats::TumWriter tum(estimate_out);
      for (const auto& p : evaluator.Estimate()) tum.Pose(p.stamp, p.pose);
      tum.Close();
    }
    return PrintSummaryAndJudge(evaluator, node, bar, "") ? 0 : 1;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc watch: " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc watch: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
