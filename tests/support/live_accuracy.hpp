// Test helper: the demo's accuracy bar for the poses a live run published
// from 1 s after some start on (a restart, a pose found or given), judged and
// printed alike by the tests that start or re-start the localisation mid-run.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "structloc/replay/trajectory_error.hpp"

namespace structloc::testing {

// Every estimated pose stamped more than 1 s after `start`, against the truth.
inline replay::TrajectoryError ErrorFromOneSecondAfter(
    const std::vector<log_formats::StampedPose>& estimate,
    const std::vector<log_formats::StampedPose>& truth, double start) {
  std::vector<log_formats::StampedPose> after;
  for (const auto& e : estimate) {
    if (e.stamp > start + 1.0) after.push_back(e);
  }
  return replay::CompareTrajectories(after, truth, 0.011);
}

// Prints the figures behind `what` and checks the demo's bar: more than 10
// poses, RMSE <= 10 mm, max <= 30 mm.
inline void ExpectDemoAccuracy(const replay::TrajectoryError& e, const std::string& what) {
  std::printf("%s, from 1 s after it: %zu poses, RMSE %.2f mm, max %.2f mm\n", what.c_str(),
              e.matched, 1e3 * e.position_rmse_m, 1e3 * e.position_max_m);
  EXPECT_GT(e.matched, 10u) << what;
  EXPECT_LE(e.position_rmse_m, 0.01) << what;
  EXPECT_LE(e.position_max_m, 0.03) << what;
}

}  // namespace structloc::testing
