// SLAM from raw odometry and scans (see header).
#include "structloc/slam_core/slam.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <utility>

#include "parallel_for.hpp"

namespace structloc::slam_core {
namespace {

// The scans since the last keyframe held for matching at most (a few MB at
// most of their points).
constexpr size_t kMaxPendingScans = 64;

Eigen::Matrix3d Information(const Eigen::Matrix3d& covariance) {
  return covariance.inverse();
}

}  // namespace

Slam::Slam(const SlamOptions& options) : options_(options) {
  options_.Validate();
  options_.match.hold_unpinned = options_.partial_matches;
}

void Slam::Add(const SlamScan& scan) {
  ++stats_.scans;
  if (keyframes_.empty()) {
    KeepKeyframe(scan, scan.odometry);
  } else {
    const geometry::Pose2D odometry = geometry::Between(keyframes_.back().odometry, scan.odometry);
    if (odometry.Translation().norm() < options_.keyframe_distance_m &&
        std::abs(odometry.theta) < options_.keyframe_angle_rad) {
      travel_since_loop_m_ += odometry.Translation().norm();
      scans_.push_back({scan.stamp, keyframes_.size() - 1, geometry::Pose2D{}});
      pending_.push_back({scans_.size() - 1, odometry, scan.points});
      // A robot standing still adds no keyframe: its scans are matched in
      // batches meanwhile (against the same submap, so as they would be).
      if (pending_.size() >= kMaxPendingScans) MatchSteps(nullptr);
      return;
    }
    AddKeyframe(scan, odometry);
  }
  scans_.push_back({scan.stamp, keyframes_.size() - 1, geometry::Pose2D{}});
}

Slam::Step Slam::Judge(const geometry::Pose2D& odometry, const ScanMatch& match) const {
  Step out;
  out.odometry = odometry;
  out.match = match;
  const double travel = odometry.Translation().norm();
  const geometry::Pose2D correction = geometry::Between(odometry, match.pose);
  const bool agrees =
      match.inlier_share >= options_.min_match_share &&
      correction.Translation().norm() <=
          options_.max_match_correction_m + options_.max_match_correction_share * travel;
  out.taken = agrees && match.constrained;
  out.partial = agrees && !match.constrained && options_.partial_matches;
  return out;
}

Slam::Step Slam::MatchSteps(const SlamScan* keyframe, const geometry::Pose2D& odometry) {
  const size_t count = pending_.size() + (keyframe ? 1 : 0);
  if (keyframes_.empty() || count == 0) return {};
  const int last = static_cast<int>(keyframes_.size()) - 1;
  std::vector<ReferencePoints> references;
  references.emplace_back(Reference(last - options_.submap_keyframes + 1, last, last),
                          options_.match);
  // A copy for each further thread: a reference finds its points' surfaces
  // as lookups need them (not thread-safe), and the copies find the same.
  const size_t workers = ParallelWorkers(count, options_.threads);
  references.reserve(workers);
  while (references.size() < workers) references.push_back(references.front());
  std::vector<ScanMatch> matches(count);
  ParallelFor(count, options_.threads, [&](size_t i, size_t worker) {
    const bool pending = i < pending_.size();
    matches[i] = MatchScan(references[worker], pending ? pending_[i].points : keyframe->points,
                           pending ? pending_[i].odometry : odometry, options_.match);
  });
  for (size_t i = 0; i < pending_.size(); ++i)
    scans_[pending_[i].scan].offset = Judge(pending_[i].odometry, matches[i]).Pose();
  pending_.clear();
  return keyframe ? Judge(odometry, matches.back()) : Step{};
}

std::vector<Eigen::Vector2d> Slam::Reference(int first, int last, int frame) const {
  first = std::max(first, 0);
  last = std::min(last, static_cast<int>(keyframes_.size()) - 1);
  std::vector<Eigen::Vector2d> points;
  for (int k = first; k <= last; ++k) {
    const geometry::Pose2D to_frame = geometry::Between(poses_[frame], poses_[k]);
    for (const auto& p : keyframes_[k].points) points.push_back(to_frame.Apply(p));
  }
  return points;
}

void Slam::AddKeyframe(const SlamScan& scan, const geometry::Pose2D& step) {
  const int last = static_cast<int>(keyframes_.size()) - 1;
  // The step as the keyframes before see it, else as odometry counted it.
  const Step matched = MatchSteps(&scan, step);
  const double travel = step.Translation().norm();
  travel_since_loop_m_ += travel;
  PoseGraphEdge edge;
  edge.from = last;
  edge.to = last + 1;
  if (matched.taken) {
    edge.measured = matched.match.pose;
    edge.information = Information(matched.match.covariance);
  } else {
    if (!matched.partial) ++stats_.odometry_edges;
    edge.measured = step;
    const double sxy =
        std::max(options_.odometry_min_sigma_xy_m, options_.odometry_sigma_per_m * travel);
    const double st = std::max(options_.odometry_min_sigma_theta_rad,
                               options_.odometry_sigma_per_rad * std::abs(step.theta) +
                                   options_.odometry_sigma_theta_per_m * travel);
    edge.information =
        Eigen::Vector3d(1 / (sxy * sxy), 1 / (sxy * sxy), 1 / (st * st)).asDiagonal();
  }
  edges_.push_back(edge);
  if (matched.partial) {
    // What the match pins, beside odometry's step (which pins the rest); the
    // match places the keyframe, so that the next keyframes are not matched
    // against a submap bent by odometry's heading drift.
    PoseGraphEdge partial = edge;
    partial.measured = matched.match.pose;
    partial.information = Information(matched.match.covariance);
    edges_.push_back(partial);
    ++stats_.partial_matches;
  }
  KeepKeyframe(
      scan, geometry::Compose(poses_[last], matched.partial ? matched.match.pose : edge.measured));
  CloseLoops(last + 1);
}

void Slam::KeepKeyframe(const SlamScan& scan, const geometry::Pose2D& estimate) {
  keyframes_.push_back({scan.odometry, scan.points});
  poses_.push_back(estimate);
  segments_.push_back(options_.walls.enabled ? FindKeyframeSegments(scan.points)
                                             : std::vector<KeyframeSegment>{});
  ++stats_.keyframes;
}

void Slam::CloseLoops(int k) {
  const double radius =
      std::min(options_.loop_max_radius_m,
               options_.loop_radius_m + options_.loop_radius_per_m * travel_since_loop_m_);
  std::vector<std::pair<double, int>> near;
  for (int j = 0; j + options_.loop_min_separation <= k; ++j) {
    const double d = (poses_[j].Translation() - poses_[k].Translation()).norm();
    if (d <= radius) near.push_back({d, j});
  }
  std::sort(near.begin(), near.end());
  if (near.size() > static_cast<size_t>(options_.loop_candidates))
    near.resize(options_.loop_candidates);
  // Each candidate matched against its own submap, on `threads` threads; the
  // loops close in the candidates' order.
  std::vector<ScanMatch> matches(near.size());
  ParallelFor(near.size(), options_.threads, [&](size_t i, size_t) {
    const int j = near[i].second;
    const ReferencePoints reference(
        Reference(j - options_.loop_submap_keyframes, j + options_.loop_submap_keyframes, j),
        options_.loop_match);
    matches[i] = MatchScan(reference, keyframes_[k].points, geometry::Between(poses_[j], poses_[k]),
                           options_.loop_match);
  });
  const size_t edges_before = edges_.size();
  for (size_t i = 0; i < near.size(); ++i) {
    ++stats_.loops_tried;
    const ScanMatch& match = matches[i];
    if (!match.constrained || match.inlier_share < options_.loop_min_share ||
        match.rms_m > options_.loop_max_rms_m) {
      continue;
    }
    PoseGraphEdge edge;
    edge.from = near[i].second;
    edge.to = k;
    edge.measured = match.pose;
    edge.information = Information(match.covariance);
    edge.robust = true;
    edges_.push_back(edge);
  }
  const size_t closed = edges_.size() - edges_before;
  if (closed == 0) return;
  stats_.loops_closed += closed;
  travel_since_loop_m_ = 0.0;
  Optimise();
}

void Slam::Optimise() {
  OptimisePoseGraph(poses_, edges_, options_.graph);
  ++stats_.optimisations;
}

void Slam::Finish() {
  MatchSteps(nullptr);
  Optimise();
  if (options_.walls.enabled)
    stats_.walls = RefineWithWalls(poses_, segments_, edges_, options_.walls, options_.graph);
}

ScansAsTaken AsTaken(const SlamOptions& options, const std::vector<double>& stamps,
                     const std::vector<geometry::Pose2D>& odometry,
                     std::vector<std::vector<Eigen::Vector2d>> points,
                     const PointTimes& point_times, ScanLatencyEstimate* estimate) {
  ScansAsTaken taken;
  taken.latency_s = options.scan_latency_s;
  if (options.estimate_scan_latency) {
    const ScanLatencyEstimate e = EstimateScanLatency(stamps, odometry, points, options.latency,
                                                      options.match, point_times, options.threads);
    taken.latency_s = e.Applied();
    if (estimate) *estimate = e;
  }
  taken.odometry = OdometryBefore(stamps, odometry, taken.latency_s);
  taken.points = DeskewedPoints(stamps, odometry, std::move(points), point_times, taken.latency_s);
  return taken;
}

std::vector<log_formats::StampedPose> Slam::Trajectory() const {
  std::vector<log_formats::StampedPose> out;
  out.reserve(scans_.size());
  for (const auto& s : scans_) {
    out.push_back({s.stamp, geometry::Compose(poses_[s.keyframe], s.offset)});
  }
  return out;
}

}  // namespace structloc::slam_core
