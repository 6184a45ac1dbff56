// How fresh a subscriber's newest pose is: from the arrival times of the
// poses, the age of the newest one as a function of time is a sawtooth (it
// grows until the next pose arrives); its quantiles over the time poses flow
// (first to last arrival) say how stale a robot's pose can get, e.g. the 95th
// percentile that the packet-loss test judges. DDS-free.
#pragma once

#include <vector>

namespace structloc::evaluation {

// The age, in seconds, that the newest pose stays at or below for a fraction
// `q` (0..1) of the time between the first and the last arrival.
// `arrivals_s`: arrival times in seconds, non-decreasing. 0 for fewer than two.
double NewestPoseAgeQuantile(const std::vector<double>& arrivals_s, double q);

}  // namespace structloc::evaluation
