// The newest pose's age quantiles (pose_age.hpp) against sawtooths worked out
// by hand: evenly spaced poses, and a stream with one long outage.
#include <gtest/gtest.h>

#include "structloc/evaluation/pose_age.hpp"

namespace structloc {
namespace {

TEST(PoseAge, EvenlySpacedPosesAgeUniformlyUpToTheirPeriod) {
  std::vector<double> arrivals;
  for (int i = 0; i <= 100; ++i) arrivals.push_back(5.0 + 0.1 * i);
  EXPECT_NEAR(evaluation::NewestPoseAgeQuantile(arrivals, 0.95), 0.095, 1e-9);
  EXPECT_NEAR(evaluation::NewestPoseAgeQuantile(arrivals, 0.5), 0.05, 1e-9);
  EXPECT_NEAR(evaluation::NewestPoseAgeQuantile(arrivals, 1.0), 0.1, 1e-9);
  EXPECT_EQ(evaluation::NewestPoseAgeQuantile({1.0}, 0.95), 0.0);
}

TEST(PoseAge, AnOutageHoldsTheTailOfTheAge) {
  // 90 gaps of 0.1 s and one of 1 s: 10 s in all. The age exceeds a > 0.1 s
  // only in the outage, for (1 - a) s: 5 % of the time (0.5 s) at a = 0.5 s.
  std::vector<double> arrivals = {0.0};
  for (int i = 0; i < 90; ++i) arrivals.push_back(arrivals.back() + 0.1);
  arrivals.push_back(arrivals.back() + 1.0);
  EXPECT_NEAR(evaluation::NewestPoseAgeQuantile(arrivals, 0.95), 0.5, 1e-9);
  EXPECT_NEAR(evaluation::NewestPoseAgeQuantile(arrivals, 1.0), 1.0, 1e-9);
}

}  // namespace
}  // namespace structloc
