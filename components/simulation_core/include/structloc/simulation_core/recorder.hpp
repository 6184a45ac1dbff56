// Runs a scenario to its end without DDS and writes a recording into a
// folder: run.clf (CARMEN ODOM + ROBOTLASER1), truth.tum (ground truth at every
// scan), initial_pose ("x y theta" of the robot at the first laser line, map
// frame) and encoders.csv (the calibration's format).
#pragma once

#include <string>

#include "structloc/simulation_core/scenario.hpp"

namespace structloc::simulation_core {

struct RecordingSummary {
  int scans = 0;
  int odometry_lines = 0;
  double duration_s = 0.0;
  double odometry_final_error_m = 0.0;  // dead reckoning vs truth at the end
};

RecordingSummary RecordScenario(const Scenario& scenario, const std::string& out_dir);

}  // namespace structloc::simulation_core
