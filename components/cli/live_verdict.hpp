// The accuracy bar a live run of the office scenario must meet and the summary
// that reports it: one definition for "structloc demo" and "structloc watch",
// so a checker in a container or another network namespace judges exactly
// what the demo promises.
#pragma once

#include <cstddef>
#include <string>

#include "structloc/dds_common/node.hpp"
#include "structloc/evaluation/live_evaluator.hpp"

namespace structloc::cli {

struct LiveBar {
  double max_rmse_m = 0.010;          // position RMSE against ground truth
  double max_error_m = 0.030;         // largest position error
  double max_heading_rmse_deg = 0.3;  // heading RMSE
  size_t min_poses = 500;             // poses matched to ground truth
  // 95th percentile of the newest pose's age while poses flow (pose_age.hpp);
  // 0 = printed, not judged.
  double max_pose_age_p95_s = 0.0;
};

// Prints the localised and odometry-only errors and every problem (peer
// problems of `node`, a missed bar; `hint` follows a missed bar). Returns
// true when the run met `bar`, was never lost and no peer problem was seen.
bool PrintSummaryAndJudge(evaluation::LiveEvaluator& evaluator, dds_common::Node& node,
                          const LiveBar& bar, const std::string& hint);

}  // namespace structloc::cli
