// Whether a tracked robot is at the twin of its tracked place (FindMapTwins):
// carried there (a kidnapping no share can reveal: the tracked pose explains
// the scans as well as the true one but for the map's one differing detail)
// or committed there. Each time the robot has moved an evidence step (the
// hypotheses' evidence_step_m or evidence_step_rad), the watch weighs the
// scan at the tracked pose and at each of its twins with the hypotheses'
// likelihood-field model (GlobalLocaliser::FitAt) and counts the difference
// as readings_per_step independent readings, as HypothesisTracker counts a
// step (one scan a step here, the twin not refitted: it is the tracked pose
// carried by the map's motion). The evidence for each twin is a CUSUM
// (Page's test: the sum of the log-likelihood ratios less a reference value,
// the worth of allowance_points points, restarted at zero whenever it would
// fall below): where the map is the same at both places it stays at zero,
// where the differing detail is in view it falls for the tracked pose when
// that is right and rises for the twin when it is. A twin is decided for
// when its evidence reaches the hypotheses' decision_log_ratio (Wald's
// bound) and it explains the scan better than the tracked pose and as well
// as a pose rightly tracked does (a robot carried elsewhere, that neither
// pose explains, is the kidnap watch's). Off the latency path (one check
// per evidence step); DDS-free.
#pragma once

#include <optional>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/localisation_core/global/global_localiser.hpp"
#include "structloc/localisation_core/global/hypothesis_tracker.hpp"

namespace structloc::localisation_core {

// A twin decided for: the robot is at `twin`, not at `tracked`.
struct TwinDecision {
  double stamp = 0.0;
  geometry::Pose2D tracked;  // robot pose tracked then (map frame)
  geometry::Pose2D twin;     // its twin, where the scans place the robot
  double since = 0.0;        // stamp from which the evidence rose without a restart
};

class TwinWatch {
 public:
  // `localiser` must outlive the watch; `sensor_mount`: the laser on the
  // robot; `twins`: the map's (FindMapTwins); `test`: the hypotheses'
  // evidence model and decision bound; `allowance_points`: see
  // MapTwinOptions.
  TwinWatch(const GlobalLocaliser& localiser, const geometry::Pose2D& sensor_mount,
            std::vector<geometry::Pose2D> twins, const HypothesisOptions& test,
            double allowance_points);

  // Whether Observe at the robot's tracked pose weighs a scan (the map has
  // twins and the robot moved an evidence step since the last weighed).
  bool Due(const geometry::Pose2D& tracked) const;
  // After a tracked scan (laser-frame points) at `stamp`: when Due, weighs
  // it and returns the twin decided for, if one is; a twin decided for
  // explains at least `min_share` of the scan (and the hypotheses' min_share).
  std::optional<TwinDecision> Observe(const std::vector<Eigen::Vector2d>& laser_points,
                                      double stamp, const geometry::Pose2D& tracked,
                                      double min_share);
  const std::vector<geometry::Pose2D>& Twins() const { return twins_; }
  // Forgets the evidence (a new pose: the tracking starts again).
  void Clear();

 private:
  const GlobalLocaliser& localiser_;
  geometry::Pose2D mount_;
  std::vector<geometry::Pose2D> twins_;
  HypothesisOptions test_;
  double allowance_;  // per step, in the evidence's units
  std::optional<geometry::Pose2D> last_weighed_;
  std::vector<double> evidence_;  // per twin: the CUSUM of its log-likelihood ratio
  std::vector<double> since_;     // per twin: when its evidence last left zero
};

}  // namespace structloc::localisation_core
