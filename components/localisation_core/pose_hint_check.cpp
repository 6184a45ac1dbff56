// Confirming a pose hint by a local search (see header).
#include "structloc/localisation_core/pose_hint_check.hpp"

#include <stdexcept>
#include <utility>

namespace structloc::localisation_core {

PoseHintCheck::PoseHintCheck(const SessionState& hint, std::string source,
                             const PoseHintCheckOptions& options)
    : hint_(hint), source_(std::move(source)), options_(options) {
  if (!(options.radius_m > 0.0) || !(options.heading_rad > 0.0) ||
      !(options.tie_distance_m >= 0.0) || !(options.tie_heading_rad >= 0.0) ||
      options.attempts < 1) {
    throw std::invalid_argument(
        "pose hint check: radius_m and heading_rad must be positive, tie_distance_m and "
        "tie_heading_rad not negative, attempts at least 1");
  }
}

PoseHintCheck::Outcome PoseHintCheck::Check(const GlobalStart& search, const SessionScan& scan,
                                            const geometry::Pose2D& odometry_at_scan) {
  Outcome outcome;
  outcome.predicted = geometry::Compose(hint_.map_to_odom, odometry_at_scan);
  auto attempt = search.TryNear(scan, outcome.predicted, options_.radius_m, options_.heading_rad);
  if (!attempt.found && attempt.result.decision == GlobalDecision::kAmbiguous)
    attempt.found = search.NearestOfTie(scan, attempt.result, outcome.predicted,
                                        options_.tie_distance_m, options_.tie_heading_rad);
  outcome.result = std::move(attempt.result);
  ++tried_;
  if (attempt.found) {
    outcome.verdict = Verdict::kFound;
    outcome.found = attempt.found;
  } else {
    outcome.verdict = tried_ >= options_.attempts ? Verdict::kGiveUp : Verdict::kTryAgain;
  }
  return outcome;
}

}  // namespace structloc::localisation_core
