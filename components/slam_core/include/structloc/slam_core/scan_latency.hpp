// How long before its stamp a recording's scan was taken, from the recording
// itself. A laser that sends its readings over a slow line (a SICK LMS at
// 38400 baud needs about 0.2 s for 361 readings) is stamped when they
// arrive, and the odometry a log gives each scan is the odometry at that
// stamp: in a quick turn the step between two scans' odometry is then off by
// the turn rate's change times the latency, degrees on a 0.3 m step. The
// latency is found as the one that best reconciles the rotations consecutive
// scans match by ICP with odometry's, sampled at each stamp minus it (a
// temporal calibration in the spirit of Furgale, Rehder and Siegwart 2013,
// rotation only, where the latency shows); no ground truth enters it. DDS-free.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/slam_core/scan_matcher.hpp"

namespace structloc::slam_core {

struct ScanLatencyOptions {
  double max_latency_s = 0.5;  // searched from -max (odometry late) to +max (scan late)
  double step_s = 0.005;       // the search's grid
  // A pair of consecutive scans enters when the latency could move its
  // odometric rotation by this much over the searched range (a turn that
  // speeds up or slows down; a steady drive says nothing about it) ...
  double min_sensitivity_rad = 0.01;
  // ... and its match explains this share of the later scan this tightly.
  double min_share = 0.5;
  double max_rms_m = 0.05;
  double huber_rad = 0.035;  // the rotation residual's robust loss, past 2 deg
  int max_pairs = 1500;      // evenly spread over the log, to bound the time
  // Rounds of matching, each from the last estimate (a pair in a quick turn
  // matches only from a guess near its latency).
  int rounds = 2;
};

struct ScanLatencyEstimate {
  double latency_s = 0.0;  // the scan was taken this long before its stamp
  size_t pairs = 0;        // consecutive scans whose matches entered
  // The matched rotations against odometry's, RMS over those pairs, at no
  // latency and at the estimate.
  double rms_at_zero_rad = 0.0;
  double rms_at_estimate_rad = 0.0;
};

// Each pose of `odometry` (stamped `stamps`, increasing) replaced by the pose
// at its stamp minus `latency_s`, linear between neighbouring samples (beyond
// the ends, along the first or last step); unchanged at no latency. Throws
// std::invalid_argument when the sizes differ or, at a latency, the stamps
// do not increase (naming the first that does not).
std::vector<geometry::Pose2D> OdometryBefore(const std::vector<double>& stamps,
                                             const std::vector<geometry::Pose2D>& odometry,
                                             double latency_s);

// The latency of scans `points` (laser frame) against their `odometry`
// (the laser's odometric pose at `stamps`). Throws std::invalid_argument as
// OdometryBefore does, for options out of range, or when no pair of scans
// tells the latency (a log without turns), saying so.
ScanLatencyEstimate EstimateScanLatency(const std::vector<double>& stamps,
                                        const std::vector<geometry::Pose2D>& odometry,
                                        const std::vector<std::vector<Eigen::Vector2d>>& points,
                                        const ScanLatencyOptions& options = {},
                                        const ScanMatchOptions& match = {});

}  // namespace structloc::slam_core
