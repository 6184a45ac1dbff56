// Whether a tracked robot may have been carried elsewhere (kidnapped: lifted,
// pushed, towed, its odometry seeing nothing). The tracker then follows a
// pose the scans no longer fit, and a local search around it finds nothing.
// After each tracked scan the watch asks how much of the scan the map
// explains at the tracked pose (GlobalLocaliser::FitAt, every
// check_period_s); when the tracker says "lost", or the share stays below
// unexplained_share, for `after_s` of scans in a row, it asks for a global
// search (the waits between them doubling while the doubt lasts, and the
// searches held to a budget of work per scan, so that a map that explains
// little of a building cannot make the watch cost more than a lost tracker
// may). The caller searches (GlobalStart), says what the search cost
// (Spent), and moves the robot only if the pose found or
// committed is far from the tracked one and explains the scan clearly better
// (Jumped); a search that finds the robot where it is tracked leaves the
// tracking alone. DDS-free.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/localisation_core/global/global_localiser.hpp"

namespace structloc::localisation_core {

struct KidnapOptions {
  // Below: the tracked pose does not explain the scan (a pose explaining
  // less than half of it is not one the global search would call found) ...
  double unexplained_share = 0.5;
  // ... nor does it when the share falls this far below its running mean
  // outside doubt (a robot carried a metre or two keeps a pose that still
  // explains half of the scan).
  double max_share_drop = 0.2;
  double after_s = 3.0;         // lost or unexplained this long: search the whole map
  double check_period_s = 0.5;  // the share is computed this often (off the latency path)
  // While in doubt, a search this long after the one before, the wait
  // doubling after each (a map that explains little of a place, where the
  // tracking is right, must not keep a search running), up to the longest.
  double search_period_s = 2.0;
  double max_search_period_s = 30.0;
  // The searches' budget, in GlobalSearch's work units (one: a scan point
  // looked up; a whole-map search runs at about 5e8 a second on our
  // machines, 1e8 for a 40 m building). Each scan observed adds
  // search_work_per_scan, about 0.5 ms: the lost-mode budget of 1 ms of CPU
  // a scan less the tracking's 0.2-0.4 ms with its work between scans. A
  // search starts only when the budget holds the work the last one took;
  // it saves up at most search_work_banked (one such search at once after a
  // calm spell).
  double search_work_per_scan = 2.5e5;
  double search_work_banked = 1e8;
  // A pose found this far from the tracked one is a kidnapping (nearer: the
  // tracker was right).
  double min_jump_m = 0.3;
  double min_jump_rad = 10.0 * geometry::kPi / 180.0;
  // ... and explaining at least this much more of the scan than the tracked
  // one, and no less than this much below what the tracked pose explained
  // while all was well (its running mean outside doubt): a map of part of a
  // building explains little where the robot goes beyond it, and a place
  // elsewhere that fits the scan a little better is no place to jump to.
  double min_share_gain = 0.15;
  double max_share_below_normal = 0.1;
  int fit_points = 90;  // scan points the share is computed with
};

// Throws std::invalid_argument naming the option when one is out of range.
void CheckKidnapOptions(const KidnapOptions& options);

// A kidnapping found: when, where the tracker had the robot and where it is.
struct Kidnapping {
  double stamp = 0.0;
  geometry::Pose2D from;  // robot pose tracked then (map frame)
  geometry::Pose2D to;    // robot pose found
  // How long the scans were unexplained before it was found (found by the
  // twin watch: how long its evidence rose).
  double doubt_s = 0.0;
};

class KidnapWatch {
 public:
  // `localiser` must outlive the watch; `sensor_mount`: the laser on the robot.
  KidnapWatch(const GlobalLocaliser& localiser, const geometry::Pose2D& sensor_mount,
              const KidnapOptions& options = {});

  // After a tracked scan (laser-frame points) at `stamp`, with the robot's
  // tracked pose and the tracker's lost verdict. True when a global search
  // is due now; the caller says Searched when it starts one.
  bool Observe(const std::vector<Eigen::Vector2d>& laser_points, double stamp,
               const geometry::Pose2D& tracked, bool lost);
  // A search for the scan at `stamp` was started: the next waits longer.
  void Searched(double stamp);
  // A search (due or not: the hypotheses' own) took `work` units.
  void Spent(uint64_t work);
  double Budget() const { return budget_; }
  // Whether the budget holds a search like the last one.
  bool CanAfford() const { return budget_ >= last_work_; }
  // Whether Observe at `stamp` computes the share (and so needs the scan's
  // points; otherwise it may be given none).
  bool CheckDue(double stamp, bool lost) const {
    return !lost && (!last_check_s_ || stamp - *last_check_s_ >= options_.check_period_s);
  }
  // How `found` (a robot pose) compares with `tracked` on a scan
  // (laser-frame points): at least min_jump_m or min_jump_rad away, explaining
  // at least min_share_gain more, and no less than max_share_below_normal
  // below the normal share. Jumped requires all three.
  struct Comparison {
    bool far = false;
    bool better = false;
    bool as_well_as_normal = false;
  };
  // What a global search for the scan at `stamp` (its laser-frame points)
  // found (a found or committed robot pose), with the pose tracked then: the
  // kidnapping (and the doubt ended) if far from it and explaining the scan
  // clearly better; nullopt (the doubt goes on) otherwise. The normal share
  // is not lowered to what a doubted pose explains, even when a search finds
  // the robot there: in a part of the building the map lacks, a place
  // elsewhere that fits a little better would then pass for the robot's.
  // `comparison`, when given, receives how the two compared.
  std::optional<Kidnapping> Jumped(double stamp, const std::vector<Eigen::Vector2d>& laser_points,
                                   const geometry::Pose2D& found, const geometry::Pose2D& tracked,
                                   Comparison* comparison = nullptr);
  Comparison Compare(const std::vector<Eigen::Vector2d>& laser_points,
                     const geometry::Pose2D& found, const geometry::Pose2D& tracked) const;
  bool ClearlyBetter(const std::vector<Eigen::Vector2d>& laser_points,
                     const geometry::Pose2D& found, const geometry::Pose2D& tracked) const {
    const auto c = Compare(laser_points, found, tracked);
    return c.far && c.better && c.as_well_as_normal;
  }
  // A search made for another reason (TwinWatch's) found a place that
  // explains the scan at `stamp` clearly better: the watch is in doubt at
  // once, and stays in doubt, whatever the share, until a search finds the
  // robot (far away: Jumped; or where it is tracked), Clear, or
  // max_search_period_s have passed. A share that sank slowly (a robot
  // carried to a place like the one it was in) may have pulled the running
  // mean down with it.
  void Doubt(double stamp);
  bool InDoubt() const { return doubt_since_.has_value() && doubt_s_ >= options_.after_s; }
  std::optional<double> LastShare() const { return last_share_; }
  std::optional<double> NormalShare() const { return normal_share_; }
  const KidnapOptions& Options() const { return options_; }
  void Clear();

 private:
  const GlobalLocaliser& localiser_;
  geometry::Pose2D mount_;
  KidnapOptions options_;
  std::optional<double> last_check_s_, last_search_s_, doubt_since_, last_share_;
  std::optional<double> normal_share_;  // running mean of the share outside doubt
  double doubt_s_ = 0.0;
  double search_period_s_;            // the wait before the next search in doubt
  double budget_;                     // work units the searches may still spend
  double last_work_ = 0.0;            // of the last search
  std::optional<double> told_until_;  // Doubt's doubt lasts until then at most
};

}  // namespace structloc::localisation_core
