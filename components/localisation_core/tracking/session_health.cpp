// The localisation's health headline and counters (see header).
#include "structloc/localisation_core/tracking/session_health.hpp"

#include <algorithm>

namespace structloc::localisation_core {
namespace {

std::string Seconds(double s) {
  return std::to_string(s).substr(0, 4);
}

}  // namespace

SessionHealth AssessHealth(const TrackingSession& session, const HealthInputs& in) {
  const SessionOptions& o = session.Options();
  SessionHealth health;
  // A source silent for a while is a warning; for long, an error.
  auto silence = [&](double since, const std::string& what) {
    const double silent = in.now_s - since;
    health.level = silent > o.silent_error_after_s ? HealthLevel::kError : HealthLevel::kWarn;
    health.message = what + " for " + Seconds(silent) + " s";
  };
  if (!in.peer_problems.empty()) {
    health.level = HealthLevel::kError;
    health.message = in.peer_problems.front();
  } else if (in.last_odometry_s == 0.0) {
    silence(in.started_s, "no odometry on " + in.odometry_topic + " yet");
  } else if (!session.HasInitialPose()) {
    health.level = HealthLevel::kWarn;
    health.message =
        "no initial pose: publish one on " + in.initial_pose_topic + " or pass --initial-pose";
  } else if (in.now_s - std::max(in.last_scan_s, in.started_s) > o.scan_timeout_s) {
    silence(std::max(in.last_scan_s, in.started_s), in.last_scan_s == 0.0
                                                        ? "no scans on " + in.scan_topic + " yet"
                                                        : "no scans on " + in.scan_topic);
  } else if (in.now_s - in.last_odometry_s > o.scan_timeout_s) {
    silence(in.last_odometry_s, "no odometry on " + in.odometry_topic);
  } else if (session.Lost()) {
    // Dead reckoning for a while is normal (a corridor, a crowd); for long it is not.
    health.level = session.LostTooLong(in.now_s) ? HealthLevel::kError : HealthLevel::kWarn;
    health.message = "lost (dead reckoning) for " + Seconds(session.LostFor(in.now_s)) +
                     " s: " + session.LostReason();
  } else {
    health.message = "localised";
  }

  const auto stats = session.Stats();
  const auto problem = session.LastProblem(in.now_s, o.problem_hold_s);
  health.values = {{"scans_processed", std::to_string(stats.scans_processed)},
                   {"scans_lost", std::to_string(stats.scans_lost)},
                   {"scans_dropped", std::to_string(session.Dropped())},
                   {"scans_rejected", std::to_string(stats.Rejected())},
                   {"scans_not_deskewed", std::to_string(stats.scans_not_deskewed)},
                   {"corrections_refused", std::to_string(stats.corrections_refused)},
                   {"reacquisitions", std::to_string(stats.reacquisitions)},
                   {"quality", std::to_string(session.LastQuality())},
                   {"last_problem", problem ? problem->first : ""},
                   {"last_problem_age_s", problem ? Seconds(problem->second) : ""}};
  for (size_t i = 0; i < stats.rejected.size(); ++i) {
    if (stats.rejected[i] > 0) {
      health.values.emplace_back(std::string("rejected: ") + ToString(static_cast<Rejection>(i)),
                                 std::to_string(stats.rejected[i]));
    }
  }
  return health;
}

}  // namespace structloc::localisation_core
