// A scan owned while it waits to be processed: the LaserScan geometry plus a
// copy of its ranges, and the robot's odometry pose when the source gives one
// with the scan (CARMEN FLASER lines).
#pragma once

#include <optional>
#include <vector>

#include "structloc/localisation_core/tracking/pose_tracker.hpp"

namespace structloc::localisation_core {

struct SessionScan {
  ScanInput geometry;  // its `ranges` / `count` are ignored: see View()
  std::vector<float> ranges;
  std::optional<geometry::Pose2D> odometry;

  // The scan as the tracker reads it (pointing into `ranges`).
  ScanInput View() const {
    ScanInput in = geometry;
    in.ranges = ranges.data();
    in.count = ranges.size();
    return in;
  }
  // A laser stamped when its readings arrived, `latency_s` after it took
  // them: the stamp moved back to when they were taken, and the odometry the
  // scan came with (that of its old stamp) dropped, to be interpolated at
  // the new one. Nothing changes at no latency.
  void TakenEarlier(double latency_s) {
    if (latency_s == 0.0) return;
    geometry.stamp -= latency_s;
    odometry.reset();
  }
  // Stamp of the last beam.
  double LastBeamStamp() const {
    return geometry.stamp +
           geometry.time_increment * static_cast<double>(ranges.empty() ? 0 : ranges.size() - 1);
  }
};

}  // namespace structloc::localisation_core
