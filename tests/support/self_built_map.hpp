// A recording with ground truth mapped by `structloc slam` and localised on
// the map it built, judged after one rigid alignment to the truth (a
// self-built map has a frame of its own): what the record test and the
// simulated tour's mapping test both ask of it.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "structloc/log_formats/tum_reader.hpp"
#include "structloc/replay/replay.hpp"
#include "structloc/replay/trajectory_alignment.hpp"

namespace structloc::testing {

// After one rigid motion onto the truth; errors of 1e9 m when too little matched.
inline replay::TrajectoryError Aligned(const std::vector<log_formats::StampedPose>& estimate,
                                       const std::vector<log_formats::StampedPose>& truth) {
  replay::TrajectoryError none;
  none.position_rmse_m = none.position_max_m = 1e9;
  return replay::CompareAligned(estimate, truth, 0.011).value_or(none);
}

struct SelfBuiltMapRun {
  CliResult slam;                 // `structloc slam`'s exit code and output
  double explained_percent = -1;  // of the scans' readings, by the built map
  int never_seen_walls = -1;      // built walls no scan sees
  bool picture = false;           // the path and map drawn
  std::vector<log_formats::StampedPose> path;
  replay::TrajectoryError slam_error;  // of the path
  replay::ReplayReport on_own_map;
  replay::TrajectoryError on_own_map_error;  // of the localisation on the built map
};

// Maps `replay_options.log_path` with `structloc slam` (files in `dir`) and
// replays the log on the map built, from the path's first pose, with the
// other options of `replay_options`; judged against `truth_path`.
inline SelfBuiltMapRun MapAndLocalise(const replay::ReplayOptions& replay_options,
                                      const std::string& truth_path, const std::string& dir) {
  SelfBuiltMapRun run;
  const std::string world = dir + "/slam_world.xml", path = dir + "/slam.tum";
  const std::string picture = dir + "/slam.png";
  run.slam = RunCli({"slam", "--log", replay_options.log_path, "--poses-out", path, "--out", world,
                     "--plot", picture},
                    std::chrono::seconds(300));
  if (run.slam.exit_code != 0) return run;
  std::smatch m;
  if (std::regex_search(run.slam.output, m,
                        std::regex("of a wall or pillar: ([0-9.]+) % explained")))
    run.explained_percent = std::stod(m[1]);
  if (std::regex_search(run.slam.output, m, std::regex(", ([0-9]+) never seen")))
    run.never_seen_walls = std::stoi(m[1]);
  run.picture = std::ifstream(picture).good();
  const auto truth = log_formats::ReadTum(truth_path);
  run.path = log_formats::ReadTum(path);
  if (run.path.empty()) return run;
  run.slam_error = Aligned(run.path, truth);
  std::printf("slam path, aligned: RMSE %.1f mm, max %.1f mm\n",
              1e3 * run.slam_error.position_rmse_m, 1e3 * run.slam_error.position_max_m);
  replay::ReplayOptions on_own = replay_options;
  on_own.map_path = world;
  on_own.initial_pose = run.path.front().pose;
  on_own.truth_path.clear();
  on_own.out_tum = dir + "/on_own_map.tum";
  run.on_own_map = replay::RunReplay(on_own);
  run.on_own_map_error = Aligned(run.on_own_map.estimate, truth);
  std::printf("localised on the self-built map, aligned: RMSE %.1f mm, max %.1f mm\n",
              1e3 * run.on_own_map_error.position_rmse_m,
              1e3 * run.on_own_map_error.position_max_m);
  return run;
}

// The built map checked against the scans it was built from: every wall
// seen by them, and most of their readings on a wall (people and the
// recording's noise aside), and the picture drawn.
inline void ExpectMapExplainsItsScans(const SelfBuiltMapRun& run) {
  EXPECT_GE(run.explained_percent, 80.0) << run.slam.output;
  EXPECT_EQ(run.never_seen_walls, 0) << run.slam.output;
  EXPECT_TRUE(run.picture);
}

}  // namespace structloc::testing
