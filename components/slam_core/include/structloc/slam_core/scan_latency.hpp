// How long before its stamp a recording's scan was taken, from the recording
// itself. A laser that sends its readings over a slow line (a SICK LMS at
// 38400 baud needs about 0.2 s for 361 readings) is stamped when they
// arrive, and the odometry a log gives each scan is the odometry at that
// stamp: in a quick turn the step between two scans' odometry is then off by
// the turn rate's change times the latency, degrees on a 0.3 m step. The
// latency is found as the one that best reconciles the rotations consecutive
// scans match by ICP with odometry's, sampled at each stamp minus it (a
// temporal calibration in the spirit of Furgale, Rehder and Siegwart 2013,
// rotation only, where the latency shows); no ground truth enters it. It is
// applied only where the recording shows it: a moving-block bootstrap of the
// matched pairs (Kuensch 1989) gives the estimate's interval, and one that
// holds no latency gives none. DDS-free.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
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
  // Where the scans come with their beams' times, matching goes on past
  // `rounds` while the estimate still moves by more than a step, each round
  // de-skewing the scans at the last estimate, up to this many rounds.
  int max_rounds = 6;
  // The estimate's interval at this confidence, from `resamples` resamplings
  // of the matched pairs in blocks of `block_pairs` consecutive ones (a pair
  // shares a scan with its neighbours, and a turn lasts a few pairs), drawn
  // by a generator seeded with `seed`; an interval that holds 0 applies none.
  double confidence = 0.95;
  int resamples = 200;
  int block_pairs = 10;
  uint32_t seed = 1;

  // Throws std::invalid_argument naming what is out of range ("scan_latency:
  // ..."), the keys that must agree with each other included.
  void Validate() const;
};

struct ScanLatencyEstimate {
  double latency_s = 0.0;  // the scan was taken this long before its stamp
  // The estimate's interval (options' confidence); the latency applied is
  // latency_s when the interval excludes 0 (the recording shows one), else 0.
  double interval_low_s = 0.0;
  double interval_high_s = 0.0;
  bool Shown() const { return interval_low_s > 0.0 || interval_high_s < 0.0; }
  double Applied() const { return Shown() ? latency_s : 0.0; }
  size_t pairs = 0;    // consecutive scans whose matches entered
  std::string untold;  // why the log does not tell the latency (no pairs), else empty
  // The matched rotations against odometry's, RMS over those pairs, at no
  // latency and at the estimate.
  double rms_at_zero_rad = 0.0;
  double rms_at_estimate_rad = 0.0;
};

// Each scan's points' times after its first beam, in seconds (empty: the
// log gives no beam timing, every point taken at once).
using PointTimes = std::vector<std::vector<double>>;

// Each pose of `odometry` (stamped `stamps`, increasing) replaced by the pose
// at its stamp minus `latency_s`, linear between neighbouring samples (beyond
// the ends, along the first or last step); unchanged at no latency. Throws
// std::invalid_argument when the sizes differ or, at a latency, the stamps
// do not increase (naming the first that does not).
std::vector<geometry::Pose2D> OdometryBefore(const std::vector<double>& stamps,
                                             const std::vector<geometry::Pose2D>& odometry,
                                             double latency_s);

// The latency of scans `points` (laser frame) against their `odometry`
// (the laser's odometric pose at `stamps`), with its interval. A log that
// does not tell it (stamps that do not increase; no turn that speeds up or
// slows down, or none matched well) gives no pairs, no latency shown and
// says why in `untold`. Throws std::invalid_argument when the sizes differ
// or for options out of range.
// With `point_times`, the scans are de-skewed at each round's latency
// (DeskewedPoints), so that the estimate is that of the first beam. The pairs
// are matched on `threads` threads at once (the estimate does not depend on it).
ScanLatencyEstimate EstimateScanLatency(const std::vector<double>& stamps,
                                        const std::vector<geometry::Pose2D>& odometry,
                                        const std::vector<std::vector<Eigen::Vector2d>>& points,
                                        const ScanLatencyOptions& options = {},
                                        const ScanMatchOptions& match = {},
                                        const PointTimes& point_times = {}, int threads = 1);

// The points of each scan (laser frame) moved into the laser's frame at its
// first beam, taken at its stamp less `latency_s`: each by the odometric
// motion from then to when it was measured, `point_times` later (thesis 3.6,
// EQ 45), odometry linear between its samples (those stamped no later than
// the one before left out). Unchanged without times. Takes the points to
// return them (a caller done with its own moves them in: no second copy of
// a long log's points). Throws std::invalid_argument when the sizes or the
// times do not fit the points.
std::vector<std::vector<Eigen::Vector2d>> DeskewedPoints(
    const std::vector<double>& stamps, const std::vector<geometry::Pose2D>& odometry,
    std::vector<std::vector<Eigen::Vector2d>> points, const PointTimes& point_times,
    double latency_s);

}  // namespace structloc::slam_core
