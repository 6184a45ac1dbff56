// The localisation's health, as a diagnostics headline with key values: which
// input is missing or silent, whether the robot is lost and for how long, WARN
// or ERROR, and the counters behind it. An operations policy, kept DDS-free
// beside the tracking session so that the live component only converts it
// into a diagnostics message (topic names come in as text).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "structloc/localisation_core/tracking/tracking_session.hpp"

namespace structloc::localisation_core {

enum class HealthLevel { kOk, kWarn, kError };

struct HealthInputs {
  double now_s = 0.0;
  double started_s = 0.0;                  // when the component started
  double last_scan_s = 0.0;                // arrival of the newest scan, 0 = none yet
  double last_odometry_s = 0.0;            // arrival of the newest odometry, 0 = none yet
  std::vector<std::string> peer_problems;  // from DDS discovery, one sentence each
  std::string scan_topic, odometry_topic, initial_pose_topic;
};

struct SessionHealth {
  HealthLevel level = HealthLevel::kOk;
  std::string message;
  std::vector<std::pair<std::string, std::string>> values;
};

// The caller holds whatever guards `session`. Thresholds are the session's
// options (<tracking>: scan_timeout_s, silent_error_after_s, problem_hold_s,
// lost_error_after_s).
SessionHealth AssessHealth(const TrackingSession& session, const HealthInputs& in);

}  // namespace structloc::localisation_core
