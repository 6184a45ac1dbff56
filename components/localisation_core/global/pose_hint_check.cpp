// Confirming a pose hint by a local search (see header).
#include "structloc/localisation_core/global/pose_hint_check.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace structloc::localisation_core {

PoseHintCheck::PoseHintCheck(const SessionState& hint, std::string source,
                             const PoseHintCheckOptions& options)
    : hint_(hint), source_(std::move(source)), options_(options) {
  if (!(options.radius_m > 0.0) || !(options.heading_rad > 0.0) ||
      !(options.tie_distance_m >= 0.0) || !(options.tie_heading_rad >= 0.0) ||
      options.attempts < 1 || !(options.sigmas >= 0.0) ||
      !(options.max_radius_m >= options.radius_m)) {
    throw std::invalid_argument(
        "pose hint check: radius_m and heading_rad must be positive, tie_distance_m, "
        "tie_heading_rad and sigmas not negative, max_radius_m at least radius_m, attempts at "
        "least 1");
  }
  // A NaN variance (a client's garbage) leaves the default window.
  const auto spread = [&](double variance) {
    return variance > 0.0 ? options.sigmas * std::sqrt(variance) : 0.0;
  };
  radius_m_ =
      std::min(options.max_radius_m,
               std::max(options.radius_m, spread(std::max(hint.variance.x(), hint.variance.y()))));
  heading_rad_ = std::min(geometry::kPi, std::max(options.heading_rad, spread(hint.variance.z())));
}

PoseHintCheck::Outcome PoseHintCheck::Check(const GlobalStart& search, const SessionScan& scan,
                                            const geometry::Pose2D& odometry_at_scan) {
  Outcome outcome;
  outcome.predicted = geometry::Compose(hint_.map_to_odom, odometry_at_scan);
  auto attempt = search.TryNear(scan, outcome.predicted, radius_m_, heading_rad_);
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
