// Offline replay of a CARMEN log through the same TrackingSession (scans in
// order, each once odometry covers it) as the localisation component: one TUM line per scan, a
// summary (scans used and rejected by reason, features matched, lost periods, time per update),
// and, given ground truth, the error of the estimate and of odometry alone.
// --no-map passes odometry through while still parsing, prefiltering and
// line-fitting every scan, for logs without a world model. DDS-free.
//
// Every input is read and checked before any output is opened; outputs are
// written to temporary files renamed only when the run succeeded, and never
// over an input. A run that localises no scan is an error.
//
// Without an initial pose the robot is first located globally by the start-up
// policy the localisation component follows (localisation_core::StartUpPolicy,
// its searches run inline here): the
// scans are tried one after the other against the whole map, each with the
// scans of the last metres placed by the log's odometry, until one gives a
// "found" pose; an ambiguous answer starts hypotheses that the following
// scans weigh until one is committed. That pose starts the tracking exactly
// as --initial-pose would. Scans before it are not tracked (nor scored); a
// log that ends first, or global_attempts scans when that limit is set, is
// an error.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "structloc/localisation_core/global/global_localiser.hpp"
#include "structloc/localisation_core/global/hypothesis_tracker.hpp"
#include "structloc/localisation_core/global/kidnap_watch.hpp"
#include "structloc/log_formats/carmen_reader.hpp"
#include "structloc/replay/trajectory_alignment.hpp"
#include "structloc/replay/trajectory_error.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::replay {

struct ReplayOptions {
  std::string map_path;                          // world model (unless no_map)
  std::string log_path;                          // CARMEN log (plain or .gz)
  std::optional<geometry::Pose2D> initial_pose;  // map pose of the first laser line's robot;
                                                 // none: located globally
  size_t global_attempts = 0;  // without initial_pose: scans tried before giving up (0: none)
  localisation_core::GlobalLocaliserOptions global;
  localisation_core::HypothesisOptions hypotheses;
  localisation_core::KidnapOptions kidnap;  // a tracked robot carried elsewhere
  std::string out_tum;                      // estimate, one line per scan
  std::string params_path;  // localisation parameters (default: the preset the first
                            // scan's geometry names, localisation_core::ChooseLaserPreset)
  std::string truth_path;   // optional TUM ground truth
  std::string plot_path;    // optional picture (.png)
  std::string fixes_path;   // optional fixes.csv (pose + variances) for calibration
  bool no_map = false;
  log_formats::CarmenLimits limits;       // beams per scan and lines per log
  world_model::WorldLimits world_limits;  // walls per map, coordinate bounds
  // Called every few percent of the log with the scans done so far.
  std::function<void(size_t scans, double fraction)> progress;
};

// One scan tried by the global localisation (replay without an initial pose).
struct GlobalAttempt {
  size_t scan = 0;  // laser line number in the log, from 1
  size_t line = 0;  // line in the log
  double stamp = 0.0;
  localisation_core::GlobalResult result;  // laser poses
  double seconds = 0.0;
};

struct ReplayReport {
  bool no_map = false;
  log_formats::CarmenStats log;
  size_t scans_used = 0;
  std::map<std::string, size_t> scans_rejected;  // reason -> count
  size_t scans_lost = 0;
  size_t scans_matched = 0;  // scans with at least one feature matched to the map
  size_t lost_periods = 0;
  double lost_duration_s = 0.0;
  double longest_lost_s = 0.0;
  // Where a local search found the robot again after tracking was lost.
  struct Reacquisition {
    double stamp = 0.0;
    geometry::Pose2D pose;  // robot pose after the search
    geometry::Pose2D jump;  // how far the search moved it (map frame)
  };
  std::vector<Reacquisition> reacquisitions;
  uint64_t corrections_refused = 0;  // by the whole-scan check
  uint64_t visibility_computations = 0;
  uint64_t stale_visibility_updates = 0;
  double mean_features = 0.0;
  double median_update_us = 0.0;
  double p99_update_us = 0.0;
  // The tracked scans' updates stage by stage (localisation_core::Stage, then
  // the whole update as wall time and as the thread's CPU time).
  struct TimeSummary {
    std::string what;
    double median_us = 0.0, p99_us = 0.0, max_us = 0.0, mean_us = 0.0;
  };
  std::vector<TimeSummary> stage_times;
  std::string parameters;         // the file used and why (given, or chosen from the scans)
  geometry::Pose2D sensor_mount;  // derived from the log when it has laser and robot poses
  std::optional<TrajectoryError> estimate_error;
  // The same after one rigid motion of the whole estimate onto the truth
  // (trajectory_alignment.hpp): what remains when a map has a frame of its
  // own, such as one `structloc slam` built.
  std::optional<TrajectoryError> aligned_estimate_error;
  // ... and after one similarity (a scale as well): how much of that is the
  // map's (or the truth's) scale.
  std::optional<ScaledError> scaled_estimate_error;
  std::optional<TrajectoryError> odometry_error;
  std::vector<log_formats::StampedPose> estimate;
  std::vector<GlobalAttempt> global_attempts;  // the searches; empty when an initial pose was given
  // When the pose came from hypotheses: where one was committed.
  struct Commit {
    size_t scan = 0;  // laser line number, from 1
    size_t line = 0;
    double stamp = 0.0;
    double travel_m = 0.0;  // odometric path from the search that started them
    size_t hypotheses = 0;  // started by that search
    size_t held_scans = 0;  // scans that weighed them
  };
  std::optional<Commit> commit;
  // Where the tracked robot was found carried elsewhere (odometry saw nothing).
  std::vector<localisation_core::Kidnapping> kidnappings;
  size_t kidnap_searches = 0;     // global searches made in doubt
  size_t twin_checks = 0;         // global searches checking the twin watch's decisions
  std::string kidnap_watch_off;   // why there was no kidnap watch (empty: there was)
  geometry::Pose2D initial_pose;  // robot pose tracking started from
};

// Throws std::runtime_error (or config::ConfigError) with a message a user can
// act on when an input is unusable, no scan could be localised, or an output
// could not be written; outputs are then left as they were.
ReplayReport RunReplay(const ReplayOptions& options);

// The global localisation's attempts, one line each, as printed by "structloc replay".
std::string FormatGlobalAttempts(const std::vector<GlobalAttempt>& attempts);

// The summary as printed by "structloc replay".
std::string FormatReport(const ReplayReport& report);
// The table of stage times printed by "structloc replay --timings".
std::string FormatStageTimes(const ReplayReport& report);
// Its first part: lines read, malformed lines with their reasons, scans used
// and rejected by reason (also the explanation when no scan was usable).
std::string FormatInputSummary(const ReplayReport& report);

}  // namespace structloc::replay
