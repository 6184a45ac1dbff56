// Options of a tracking session (the pose tracker's own and the session's
// timing), loaded from the <tracking> block of a <localisation_params> file,
// the same file as the Localiser's options, so that the live component and
// the offline replay run with one set of parameters.
#pragma once

#include <ostream>
#include <string>

#include "structloc/localisation_core/tracking/pose_tracker.hpp"

namespace structloc::localisation_core {

struct SessionOptions {
  TrackerOptions tracker;
  double state_period_s = 2.0;        // how often the pose is due to be saved
  double lost_error_after_s = 5.0;    // lost (dead reckoning) this long is an error, not a warning
  double scan_timeout_s = 0.5;        // health is WARN without scans (or odometry) this long
  double silent_error_after_s = 5.0;  // ... and ERROR when an input stays silent this long
  double problem_hold_s = 10.0;       // a rejected input stays in the health report this long
  // At most this many scans wait for odometry in in-order scheduling (replay);
  // beyond it the oldest is processed with what there is.
  size_t max_pending_scans = 1000;
  // Each scan was taken this long before its stamp (a laser stamped when its
  // readings arrived; `structloc slam` estimates it from a recording). The
  // adapters move a scan's stamp back by it (SessionScan::TakenEarlier).
  double scan_latency_s = 0.0;

  // Throws std::invalid_argument naming the broken option ("tracking: ...").
  void Validate() const;
};

// Reads the <tracking> block of a <localisation_params> file; every attribute
// must be present and none may be unknown. Throws config::ConfigError naming
// file, line and problem.
SessionOptions LoadSessionOptions(const std::string& path);

// Lists every key of the <tracking> block with its default, unit, valid values
// and meaning.
void PrintSessionOptions(std::ostream& out);

// Writes a complete <localisation_params> file (every section, every key) of
// the file at `path` as loaded: its own values and those it takes from its
// base. Throws config::ConfigError as the loaders do.
void WriteExpandedLocalisationParams(const std::string& path, std::ostream& out);

}  // namespace structloc::localisation_core
