// SLAM from raw odometry and scans (thesis 6.5.5: the robot maps its own
// building): a keyframe every few decimetres of travel, matched against the
// keyframes just before it (point-to-line ICP, ScanMatcher) for a relative
// pose with its covariance, odometry's step beside what the match pins where
// it pins some directions only (partial_matches), odometry's step alone where
// it fails;
// loops closed by matching the new keyframe against places seen long ago
// near where the graph puts it, accepted only where the match explains most
// of the scan tightly, and entered through a robust loss; the pose graph
// optimised with Ceres (PoseGraph) after each loop closed and at the end,
// then, where enabled, refined with the walls the keyframes see (RefineWithWalls).
// Scans between keyframes are matched against their keyframe's submap too
// (odometry's step where that fails), without entering the graph: when the
// next keyframe is, beside its match, so that both cores work (the same
// submap, so the same result). Independent matches run on `threads` threads;
// the results do not depend on how many. DDS-free.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "structloc/log_formats/tum_reader.hpp"
#include "structloc/slam_core/pose_graph.hpp"
#include "structloc/slam_core/scan_latency.hpp"
#include "structloc/slam_core/scan_matcher.hpp"
#include "structloc/slam_core/wall_refinement.hpp"

namespace structloc::slam_core {

struct SlamOptions {
  double keyframe_distance_m = 0.3;  // a keyframe after this much travel ...
  double keyframe_angle_rad = 0.25;  // ... or this much turn
  int submap_keyframes = 8;          // the keyframes a new one is matched against
  // A sequential match is taken when it explains this share of the scan and
  // moves the odometric guess by at most max_match_correction_m plus
  // max_match_correction_share of the step.
  double min_match_share = 0.5;
  double max_match_correction_m = 0.3;
  double max_match_correction_share = 0.5;
  // A match that passes those gates but pins some directions only (along a
  // corridor) enters the graph beside odometry's step and places the
  // keyframe (true), its ICP holding odometry's position along what it does
  // not pin (ScanMatchOptions::hold_unpinned), so that the heading along a
  // corridor comes from its walls; or it is dropped for odometry's step
  // (false), and the heading there drifts with odometry's.
  bool partial_matches = true;
  // Odometry's standard deviation (the edge where no match pins the step):
  // position per metre driven, heading per radian turned plus per metre
  // driven, never below the floors.
  double odometry_sigma_per_m = 0.1;
  double odometry_sigma_per_rad = 0.1;
  double odometry_sigma_theta_per_m = 0.02;
  double odometry_min_sigma_xy_m = 0.01;
  double odometry_min_sigma_theta_rad = 0.005;
  // Loop closure: keyframes at least this many before the new one ...
  int loop_min_separation = 30;
  // ... whose estimate is within this radius of the new one's, widened by
  // this share of the distance counted since the last loop closed, at most
  // the last. The count adds every scan's odometric distance from its
  // keyframe, so it runs several times faster than the path itself; the
  // radius was chosen with that count, and counting the path alone changes
  // the results (see the maps guide).
  double loop_radius_m = 2.0;
  double loop_radius_per_m = 0.05;
  double loop_max_radius_m = 8.0;
  int loop_candidates = 3;        // the nearest tried per keyframe
  int loop_submap_keyframes = 4;  // each side of the candidate, its reference
  double loop_min_share = 0.7;    // the scan explained by the old place ...
  double loop_max_rms_m = 0.05;   // ... this tightly
  ScanMatchOptions match;
  // ICP from the graph's guess, pairing from farther away than a step's.
  ScanMatchOptions loop_match{30, 2.0, 0.15, 0.25, 0.03, 10.0, 0.01, 0.003};
  PoseGraphOptions graph;
  WallRefinementOptions walls;
  // The laser's latency against odometry: each scan's odometry is taken this
  // long before its stamp (a scan stamped when its readings arrived) ...
  double scan_latency_s = 0.0;
  // ... or as the recording shows it (EstimateScanLatency: none where its
  // interval holds none), which then replaces scan_latency_s.
  bool estimate_scan_latency = true;
  ScanLatencyOptions latency;
  // Independent matches (a keyframe's loop candidates, the scans between
  // keyframes, the latency estimate's pairs) run on this many threads at
  // once; the results do not depend on it.
  int threads = 2;

  // Throws std::invalid_argument naming the section and key of a value out of
  // range.
  void Validate() const;
};

// The scans of a log as they were taken: each one's odometry at the moment
// its first beam was taken, `latency_s` before its stamp (the options'
// scan_latency_s, or with estimate_scan_latency the latency the scans show:
// EstimateScanLatency's, applied where its interval excludes none), and its
// points de-skewed to that moment where the log gives their times.
struct ScansAsTaken {
  std::vector<geometry::Pose2D> odometry;
  std::vector<std::vector<Eigen::Vector2d>> points;
  double latency_s = 0.0;
};

// `estimate` receives the estimate, when made. Takes the points to return
// them, as DeskewedPoints does. Throws std::invalid_argument as
// OdometryBefore, EstimateScanLatency and DeskewedPoints do.
ScansAsTaken AsTaken(const SlamOptions& options, const std::vector<double>& stamps,
                     const std::vector<geometry::Pose2D>& odometry,
                     std::vector<std::vector<Eigen::Vector2d>> points,
                     const PointTimes& point_times = {}, ScanLatencyEstimate* estimate = nullptr);

// A <slam_params> file (`structloc params --slam` lists its keys); throws
// config::ConfigError naming the file, line and key.
SlamOptions LoadSlamOptions(const std::string& path);
// Every key with its default, unit, valid values and meaning.
void PrintSlamOptions(std::ostream& out);
// The file at `path` whole: every key with the value it takes.
void WriteExpandedSlamOptions(const std::string& path, std::ostream& out);

// One scan: the robot's odometric pose and the readings in the robot frame.
struct SlamScan {
  double stamp = 0.0;
  geometry::Pose2D odometry;
  std::vector<Eigen::Vector2d> points;
};

struct SlamStats {
  size_t scans = 0;
  size_t keyframes = 0;
  size_t odometry_edges = 0;   // steps no match pinned
  size_t partial_matches = 0;  // steps on odometry beside a partial match (partial_matches)
  size_t loops_tried = 0;
  size_t loops_closed = 0;
  size_t optimisations = 0;
  WallRefinementSummary walls;  // the refinement that ends SLAM, when enabled
};

class Slam {
 public:
  // Throws std::invalid_argument for options out of range (SlamOptions::Validate).
  explicit Slam(const SlamOptions& options = {});
  void Add(const SlamScan& scan);
  // The final optimisation.
  void Finish();
  // The robot pose of every scan added, in the frame of the first scan's
  // odometry; after Finish (the scans since the last keyframe are matched
  // with the next keyframe or by Finish).
  std::vector<log_formats::StampedPose> Trajectory() const;
  const SlamStats& Stats() const { return stats_; }
  const std::vector<PoseGraphEdge>& Edges() const { return edges_; }

 private:
  struct Keyframe {
    geometry::Pose2D odometry;
    std::vector<Eigen::Vector2d> points;
  };
  struct ScanEntry {
    double stamp;
    size_t keyframe;
    geometry::Pose2D offset;  // its pose in the keyframe's frame
  };
  // A keyframe after the first, `step` from the last one by odometry.
  void AddKeyframe(const SlamScan& scan, const geometry::Pose2D& step);
  // Appends the keyframe with its first estimate (and its segments).
  void KeepKeyframe(const SlamScan& scan, const geometry::Pose2D& estimate);
  // The step from the last keyframe to `scan`: the match against the
  // keyframes before it, and whether it is good enough to take over
  // odometry's step.
  struct Step {
    geometry::Pose2D odometry;
    ScanMatch match;
    bool taken = false;
    bool partial = false;  // with partial_matches: passes the gates, pins not every direction
    geometry::Pose2D Pose() const { return taken ? match.pose : odometry; }
  };
  // Whether `match` of the step `odometry` from the last keyframe is taken.
  Step Judge(const geometry::Pose2D& odometry, const ScanMatch& match) const;
  // The scans since the last keyframe (pending_, whose offsets it fills) and
  // the new `keyframe`'s step, `odometry` by odometry (no keyframe at Finish:
  // nullptr), all matched against the last keyframe's submap, on `threads`
  // threads.
  Step MatchSteps(const SlamScan* keyframe, const geometry::Pose2D& odometry = {});
  // The points of keyframes first..last (clamped) in the frame of keyframe `frame`.
  std::vector<Eigen::Vector2d> Reference(int first, int last, int frame) const;
  void CloseLoops(int k);
  void Optimise();

  SlamOptions options_;
  std::vector<Keyframe> keyframes_;
  std::vector<geometry::Pose2D> poses_;  // keyframe estimates
  // Each keyframe's straight segments, for the wall refinement (when enabled).
  std::vector<std::vector<KeyframeSegment>> segments_;
  std::vector<PoseGraphEdge> edges_;
  std::vector<ScanEntry> scans_;
  // Every scan's odometric distance from its keyframe, summed since a loop
  // last closed (see loop_radius_per_m).
  double travel_since_loop_m_ = 0.0;
  // The scans since the last keyframe, matched when the next keyframe is
  // (or at Finish, or when kMaxPendingScans wait) against the same submap:
  // odometry's step from the keyframe and the points, for the offset of
  // scans_[scan].
  struct PendingScan {
    size_t scan;
    geometry::Pose2D odometry;
    std::vector<Eigen::Vector2d> points;
  };
  std::vector<PendingScan> pending_;
  SlamStats stats_;
};

}  // namespace structloc::slam_core
