// Several poses of a robot without a pose, followed until the building tells
// them apart. In a building with symmetric or repeated parts one scan (even
// with the scans of the last metres) fits several places equally well: the
// global search then answers "ambiguous". Each of its distinct candidates
// becomes a hypothesis that odometry carries along and every scan refits
// (GlobalLocaliser::Polish); each gathers evidence, the log-likelihood of the
// scans under a likelihood-field model (GlobalLocaliser::FitAt). The decision
// is Wald's sequential probability-ratio test between the leader and each
// rival: a rival whose log-likelihood falls behind the leader's by
// ln((1 - beta) / alpha) is dropped, and the last one standing is committed
// when it explains enough of the scan. With alpha = beta = 0.001 the bound is
// 6.9; those error rates hold if the evidence counted were independent, so
// neighbouring beams and scans taken from nearly the same place are counted
// as a few independent readings only (readings_per_step, evidence_step_m).
// When no hypothesis explains the scans any more, the caller searches afresh.
// DDS-free, deterministic.
#pragma once

#include <optional>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/localisation_core/global/global_localiser.hpp"

namespace structloc::localisation_core {

struct HypothesisOptions {
  int max_hypotheses = 8;    // of a search's distinct candidates, at most this many are followed
  double seed_margin = 0.2;  // ... those explaining at most this share less than the best
  int fit_points = 90;       // scan points a hypothesis is refitted with and weighed by
  // Likelihood of a reading the map does not explain (a person, a box, a
  // wall the map lacks): the floor of the likelihood-field model; a reading
  // on a wall is 1 / u times as likely.
  double unexplained_likelihood = 0.1;
  // Evidence is counted once per this much odometric travel or turn (the
  // scans in between are averaged): scans from nearly the same place repeat
  // the same information, and a robot standing still must not decide on it.
  double evidence_step_m = 0.25;
  double evidence_step_rad = 15.0 * geometry::kPi / 180.0;
  // Independent readings one step counts as: a scan sees some 5-15 distinct
  // surfaces, and a pose's error moves all the points on one surface together.
  double readings_per_step = 10.0;
  double decision_log_ratio = 6.9;  // Wald's bound ln((1 - beta) / alpha), alpha = beta = 0.001
  // Two hypotheses this close are one (the worse is dropped).
  double merge_distance_m = 0.25;
  double merge_heading_rad = 5.0 * geometry::kPi / 180.0;
  double min_share = 0.45;  // the one committed explains at least this much of its last step
  int poor_steps = 3;       // steps in a row no hypothesis explains min_share: search afresh
};

// Throws std::invalid_argument naming the option when one is out of range.
void CheckHypothesisOptions(const HypothesisOptions& options);

struct Hypothesis {
  geometry::Pose2D pose;         // robot pose in the map frame at the last scan
  double log_likelihood = 0.0;   // evidence of the steps counted
  double share = 0.0;            // of the last scan's points explained
  double step_mean_share = 0.0;  // over the scans of the last step counted
};

class HypothesisTracker {
 public:
  // `localiser` must outlive the tracker; `sensor_mount`: the laser on the robot.
  HypothesisTracker(const GlobalLocaliser& localiser, const geometry::Pose2D& sensor_mount,
                    const HypothesisOptions& options = {});

  // Starts a hypothesis from each of the result's candidates within
  // seed_margin of its best (at most max_hypotheses), for the scan whose
  // points (laser frame) were searched and the robot's odometric pose then.
  // Forgets the hypotheses held before. Returns how many were started.
  size_t Seed(const GlobalResult& result, const std::vector<Eigen::Vector2d>& laser_points,
              const geometry::Pose2D& odometry);

  enum class Verdict {
    kSearch,     // no hypothesis (left): the caller searches afresh
    kHolding,    // several hypotheses are alive
    kCommitted,  // one was chosen: Committed()
  };
  // Carries every hypothesis by odometry to this scan, refits and weighs it.
  Verdict Update(const std::vector<Eigen::Vector2d>& laser_points,
                 const geometry::Pose2D& odometry);

  bool Holding() const { return !tracks_.empty() && !committed_; }
  std::vector<Hypothesis> Hypotheses() const;  // best first
  const std::optional<Hypothesis>& Committed() const { return committed_; }
  double TravelM() const { return travel_m_; }    // odometric path since Seed, kept when given up
  size_t Seeded() const { return seeded_; }       // hypotheses started by the last Seed
  size_t StepsCounted() const { return steps_; }  // evidence steps since Seed
  void Clear();

 private:
  struct Track {
    Hypothesis h;
    double step_log_likelihood = 0.0;  // summed over the scans of the open step
    double step_share = 0.0;
    int step_scans = 0;
  };
  void Refit(Track& track, const std::vector<Eigen::Vector2d>& fit_points) const;
  void CloseStep();
  void MergeAndDrop();
  Verdict Decide();

  const GlobalLocaliser& localiser_;
  geometry::Pose2D mount_;
  HypothesisOptions options_;
  std::vector<Track> tracks_;  // best first after each Seed and Update
  std::optional<Hypothesis> committed_;
  geometry::Pose2D last_odometry_;
  double travel_m_ = 0.0;
  double step_travel_m_ = 0.0, step_turn_rad_ = 0.0;
  size_t seeded_ = 0, steps_ = 0;
  int poor_ = 0;
};

}  // namespace structloc::localisation_core
