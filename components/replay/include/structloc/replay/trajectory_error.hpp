// Errors of an estimated trajectory against ground truth, matched by time:
// position RMSE and maximum, heading RMSE. Shared by the replay and the demo.
#pragma once

#include <vector>

#include "structloc/log_formats/tum_reader.hpp"

namespace structloc::replay {

struct TrajectoryError {
  size_t matched = 0;
  double position_rmse_m = 0.0;
  double position_max_m = 0.0;
  double heading_rmse_rad = 0.0;
  double final_position_m = 0.0;
};

TrajectoryError CompareTrajectories(const std::vector<log_formats::StampedPose>& estimate,
                                    const std::vector<log_formats::StampedPose>& truth,
                                    double tolerance_s = 0.02);

}  // namespace structloc::replay
