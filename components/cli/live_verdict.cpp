// Summary and verdict of a live run (see header).
#include "live_verdict.hpp"

#include <cstdio>

#include "structloc/evaluation/pose_age.hpp"
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
  const auto arrivals = evaluator.PoseArrivals();
  const double age_p95_s = evaluation::NewestPoseAgeQuantile(arrivals, 0.95);
  std::printf("  poses received: %zu; the newest pose's age: p95 %.0f ms, max %.0f ms\n",
              arrivals.size(), 1e3 * age_p95_s,
              1e3 * evaluation::NewestPoseAgeQuantile(arrivals, 1.0));
  bool passed = true;
  if (bar.max_pose_age_p95_s > 0 && !(age_p95_s <= bar.max_pose_age_p95_s)) {
    std::printf("  FAILED the bar: the newest pose's age p95 must be <= %.0f ms\n",
                1e3 * bar.max_pose_age_p95_s);
    passed = false;
  }
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
