// Step 8 (thesis 3.6, EQ 45): scans taken while moving. Each beam was measured
// from a slightly different sensor pose; de-skewing moves every point into
// the sensor frame at the scan's reference time (its stamp, the first beam).
#pragma once

#include <vector>

#include "structloc/localisation_core/scan/scan_points.hpp"
#include "structloc/localisation_core/tracking/odometry_history.hpp"

namespace structloc::localisation_core {

// Sensor pose of every beam relative to the reference pose, as x, y and
// cos/sin of the rotation (no trigonometry when applying it).
struct BeamMotion {
  std::vector<double> x, y, c, s;
  void Reserve(size_t n);
  void Resize(size_t n);
  size_t Size() const { return x.size(); }
};

// Thesis EQ 45: linear motion in x, y, theta from the first beam (identity)
// to `first_to_last` (the last beam's sensor pose in the first beam's frame).
void LinearBeamMotion(const geometry::Pose2D& first_to_last, size_t count, BeamMotion& motion);

// From an odometry history of the robot base: beam i at stamp + i * time_increment,
// sensor = base * mount. Returns false (motion untouched) when the history does
// not cover the scan's time span.
// Beams up to `max_extrapolation_s` after the newest odometry are placed by
// extrapolating it at constant velocity.
bool BeamMotionFromHistory(const OdometryHistory& history, const geometry::Pose2D& mount,
                           double stamp, double time_increment, size_t count, BeamMotion& motion,
                           double max_extrapolation_s = 0.0);

// Moves every point (by its beam index) into the reference frame.
void Deskew(const BeamMotion& motion, ScanPoints& points);

}  // namespace structloc::localisation_core
