// Several hypotheses of a robot's pose, decided by a sequential test (see header).
#include "structloc/localisation_core/global/hypothesis_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace structloc::localisation_core {

void CheckHypothesisOptions(const HypothesisOptions& o) {
  auto require = [](bool ok, const char* name, const char* range) {
    if (!ok)
      throw std::invalid_argument(std::string("hypothesis options: ") + name + " must be " + range);
  };
  require(o.max_hypotheses >= 1 && o.max_hypotheses <= 64, "max_hypotheses", "in [1, 64]");
  require(o.seed_margin >= 0.0 && o.seed_margin <= 1.0, "seed_margin", "in [0, 1]");
  require(o.fit_points >= 10 && o.fit_points <= 5000, "fit_points", "in [10, 5000]");
  require(o.unexplained_likelihood > 0.0 && o.unexplained_likelihood < 1.0,
          "unexplained_likelihood", "in (0, 1)");
  require(o.evidence_step_m > 0.0 && o.evidence_step_m <= 10.0, "evidence_step_m", "in (0, 10]");
  require(o.evidence_step_rad > 0.0 && o.evidence_step_rad <= geometry::kPi, "evidence_step_rad",
          "in (0, pi]");
  require(o.readings_per_step > 0.0 && o.readings_per_step <= 1000.0, "readings_per_step",
          "in (0, 1000]");
  require(o.decision_log_ratio > 0.0 && o.decision_log_ratio <= 100.0, "decision_log_ratio",
          "in (0, 100]");
  require(o.merge_distance_m >= 0.0 && o.merge_heading_rad >= 0.0,
          "merge_distance_m / merge_heading_rad", "at least 0");
  require(o.min_share >= 0.0 && o.min_share <= 1.0, "min_share", "in [0, 1]");
  require(o.poor_steps >= 1, "poor_steps", "at least 1");
}

HypothesisTracker::HypothesisTracker(const GlobalLocaliser& localiser,
                                     const geometry::Pose2D& sensor_mount,
                                     const HypothesisOptions& options)
    : localiser_(localiser), mount_(sensor_mount), options_(options) {
  CheckHypothesisOptions(options_);
}

void HypothesisTracker::Clear() {
  tracks_.clear();
  committed_.reset();
  travel_m_ = step_travel_m_ = step_turn_rad_ = 0.0;
  seeded_ = steps_ = 0;
  poor_ = 0;
}

size_t HypothesisTracker::Seed(const GlobalResult& result,
                               const std::vector<Eigen::Vector2d>& laser_points,
                               const geometry::Pose2D& odometry) {
  Clear();
  if (result.candidates.empty() || !geometry::IsFinite(odometry)) return 0;
  const double floor = result.candidates.front().score - options_.seed_margin;
  const auto fit_points = localiser_.FitPoints(laser_points, options_.fit_points);
  const geometry::Pose2D unmount = geometry::Inverse(mount_);
  for (const auto& candidate : result.candidates) {
    if (tracks_.size() >= static_cast<size_t>(options_.max_hypotheses)) break;
    if (candidate.score < floor) continue;
    Track track;
    track.h.pose = geometry::Compose(candidate.pose, unmount);
    Refit(track, fit_points);
    tracks_.push_back(track);
  }
  last_odometry_ = odometry;
  seeded_ = tracks_.size();
  MergeAndDrop();
  return seeded_;
}

void HypothesisTracker::Refit(Track& track, const std::vector<Eigen::Vector2d>& fit_points) const {
  const geometry::Pose2D laser =
      localiser_.Polish(fit_points, geometry::Compose(track.h.pose, mount_));
  track.h.pose = geometry::Compose(laser, geometry::Inverse(mount_));
  const auto fit = localiser_.FitAt(fit_points, laser, options_.unexplained_likelihood);
  track.h.share = fit.share;
  track.step_log_likelihood += fit.mean_log_likelihood;
  track.step_share += fit.share;
  ++track.step_scans;
}

HypothesisTracker::Verdict HypothesisTracker::Update(
    const std::vector<Eigen::Vector2d>& laser_points, const geometry::Pose2D& odometry) {
  if (committed_) return Verdict::kCommitted;
  if (tracks_.empty()) return Verdict::kSearch;
  if (!geometry::IsFinite(odometry)) {  // the chain of odometry is broken
    Clear();
    return Verdict::kSearch;
  }
  const geometry::Pose2D delta = geometry::Between(last_odometry_, odometry);
  last_odometry_ = odometry;
  const double moved = std::hypot(delta.x, delta.y);
  travel_m_ += moved;
  step_travel_m_ += moved;
  step_turn_rad_ += std::abs(delta.theta);
  const auto fit_points = localiser_.FitPoints(laser_points, options_.fit_points);
  for (auto& track : tracks_) {
    track.h.pose = geometry::Compose(track.h.pose, delta);
    Refit(track, fit_points);
  }
  if (step_travel_m_ >= options_.evidence_step_m || step_turn_rad_ >= options_.evidence_step_rad)
    CloseStep();
  MergeAndDrop();
  return Decide();
}

// The evidence of the step: the mean log-likelihood per point over its scans,
// counted as readings_per_step independent readings.
void HypothesisTracker::CloseStep() {
  double best_share = 0.0;
  for (auto& track : tracks_) {
    if (track.step_scans == 0) continue;
    const double n = static_cast<double>(track.step_scans);
    track.h.log_likelihood += options_.readings_per_step * track.step_log_likelihood / n;
    track.h.step_mean_share = track.step_share / n;
    best_share = std::max(best_share, track.h.step_mean_share);
    track.step_log_likelihood = track.step_share = 0.0;
    track.step_scans = 0;
  }
  ++steps_;
  step_travel_m_ = step_turn_rad_ = 0.0;
  poor_ = best_share < options_.min_share ? poor_ + 1 : 0;
}

void HypothesisTracker::MergeAndDrop() {
  std::stable_sort(tracks_.begin(), tracks_.end(), [](const Track& a, const Track& b) {
    return a.h.log_likelihood > b.h.log_likelihood;
  });
  std::vector<Track> kept;
  for (const auto& track : tracks_) {
    if (!kept.empty() &&
        kept.front().h.log_likelihood - track.h.log_likelihood > options_.decision_log_ratio)
      continue;  // the test rejects it
    const bool merged = std::any_of(kept.begin(), kept.end(), [&](const Track& k) {
      return std::hypot(k.h.pose.x - track.h.pose.x, k.h.pose.y - track.h.pose.y) <=
                 options_.merge_distance_m &&
             std::abs(geometry::WrapAngle(k.h.pose.theta - track.h.pose.theta)) <=
                 options_.merge_heading_rad;
    });
    if (!merged) kept.push_back(track);
  }
  tracks_ = std::move(kept);
}

std::vector<Hypothesis> HypothesisTracker::Hypotheses() const {
  std::vector<Hypothesis> hypotheses;
  for (const auto& track : tracks_) hypotheses.push_back(track.h);
  return hypotheses;
}

HypothesisTracker::Verdict HypothesisTracker::Decide() {
  if (poor_ >= options_.poor_steps) {  // given up; TravelM() stays until the next Seed
    tracks_.clear();
    return Verdict::kSearch;
  }
  if (tracks_.size() == 1 && steps_ > 0 &&
      tracks_.front().h.step_mean_share >= options_.min_share) {
    committed_ = tracks_.front().h;
    return Verdict::kCommitted;
  }
  return Verdict::kHolding;
}

}  // namespace structloc::localisation_core
