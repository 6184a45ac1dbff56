// Summary and verdict of a live run (see header).
#include "live_verdict.hpp"

#include <cstdio>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::cli {

bool PrintSummaryAndJudge(evaluation::LiveEvaluator& evaluator, dds_common::Node& node,
                          const LiveBar& bar, const std::string& hint) {
  const auto est = evaluator.EstimateError();
  const auto odo = evaluator.OdometryError();
  const auto lost = evaluator.LostCount();
  std::printf("\nsummary (%zu poses against ground truth)\n", est.matched);
  std::printf(
      "  localised:     position RMSE %7.1f mm, max %7.1f mm, heading RMSE %.3f deg, lost %llu "
      "times\n",
      1e3 * est.position_rmse_m, 1e3 * est.position_max_m,
      est.heading_rmse_rad * 180 / geometry::kPi, static_cast<unsigned long long>(lost));
  std::printf(
      "  odometry only: position RMSE %7.1f mm, max %7.1f mm, heading RMSE %.3f deg, %.2f m off "
      "at the end\n",
      1e3 * odo.position_rmse_m, 1e3 * odo.position_max_m,
      odo.heading_rmse_rad * 180 / geometry::kPi, odo.final_position_m);
  bool passed = true;
  for (const auto& problem : node.PeerProblems()) {
    std::printf("  PROBLEM: %s\n", problem.c_str());
    passed = false;
  }
  if (est.position_rmse_m > bar.max_rmse_m || est.position_max_m > bar.max_error_m ||
      est.heading_rmse_rad * 180 / geometry::kPi > bar.max_heading_rmse_deg || lost > 0 ||
      est.matched < bar.min_poses) {
    std::printf(
        "  FAILED the bar (RMSE <= %.0f mm, max <= %.0f mm, heading RMSE <= %.1f deg, never "
        "lost, >= %zu poses)%s\n",
        1e3 * bar.max_rmse_m, 1e3 * bar.max_error_m, bar.max_heading_rmse_deg, bar.min_poses,
        hint.empty() ? "" : (": " + hint).c_str());
    passed = false;
  }
  std::fflush(stdout);
  return passed;
}

}  // namespace structloc::cli
