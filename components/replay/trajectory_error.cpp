// Trajectory comparison (see header).
#include "structloc/replay/trajectory_error.hpp"

#include <cmath>

namespace structloc::replay {

TrajectoryError CompareTrajectories(const std::vector<log_formats::StampedPose>& estimate,
                                    const std::vector<log_formats::StampedPose>& truth,
                                    double tolerance_s) {
  TrajectoryError e;
  double sum_p = 0.0, sum_h = 0.0;
  for (const auto& p : estimate) {
    const auto* t = log_formats::Nearest(truth, p.stamp, tolerance_s);
    if (t == nullptr) continue;
    const double d = (p.pose.Translation() - t->pose.Translation()).norm();
    const double h = geometry::WrapAngle(p.pose.theta - t->pose.theta);
    sum_p += d * d;
    sum_h += h * h;
    e.position_max_m = std::max(e.position_max_m, d);
    e.final_position_m = d;
    ++e.matched;
  }
  if (e.matched > 0) {
    e.position_rmse_m = std::sqrt(sum_p / e.matched);
    e.heading_rmse_rad = std::sqrt(sum_h / e.matched);
  }
  return e;
}

}  // namespace structloc::replay
