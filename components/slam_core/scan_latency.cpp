// A recording's scan latency against its odometry (see header).
#include "structloc/slam_core/scan_latency.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace structloc::slam_core {
namespace {

void CheckSizes(const std::vector<double>& stamps, size_t poses) {
  if (stamps.size() != poses)
    throw std::invalid_argument("scan latency: " + std::to_string(stamps.size()) + " stamps for " +
                                std::to_string(poses) + " poses");
}

void CheckIncreasing(const std::vector<double>& stamps) {
  for (size_t i = 1; i < stamps.size(); ++i) {
    if (!(stamps[i] > stamps[i - 1]))
      throw std::invalid_argument("scan latency: scan " + std::to_string(i) + "'s stamp " +
                                  std::to_string(stamps[i]) + " is not after the one before (" +
                                  std::to_string(stamps[i - 1]) +
                                  "); a latency needs increasing stamps (re-stamp the log)");
  }
}

// Odometry as a function of time: linear between its samples, made
// continuous in heading (no jumps of 2 pi) so that rotations over any time
// come out whole. A sample that repeats the one before exactly is left out
// (but the log's last): odometry that was not updated, because the robot
// stood still or because its messages stalled, as MIT CSAIL's do for 0.8 s
// before a single 85 deg step; its motion is then spread over the stall
// instead of put into the last interval.
class OdometryTrack {
 public:
  OdometryTrack(const std::vector<double>& stamps, const std::vector<geometry::Pose2D>& odometry) {
    for (size_t i = 0; i < odometry.size(); ++i) {
      const bool repeat = i > 0 && odometry[i].x == odometry[i - 1].x &&
                          odometry[i].y == odometry[i - 1].y &&
                          odometry[i].theta == odometry[i - 1].theta;
      if (repeat && i + 1 < odometry.size()) continue;
      heading_.push_back(poses_.empty()
                             ? odometry[i].theta
                             : heading_.back() +
                                   geometry::WrapAngle(odometry[i].theta - poses_.back().theta));
      stamps_.push_back(stamps[i]);
      poses_.push_back(odometry[i]);
    }
  }

  geometry::Pose2D PoseAt(double t) const {
    const auto [j, f] = Locate(t);
    return geometry::Interpolate(poses_[j], poses_[j + 1], f);
  }
  double HeadingAt(double t) const {
    const auto [j, f] = Locate(t);
    return heading_[j] + f * (heading_[j + 1] - heading_[j]);
  }

 private:
  // The sample `j` time `t` follows (clamped to the first and last steps) and
  // how far along the step to the next it lies (below 0 or above 1 beyond the
  // ends).
  std::pair<size_t, double> Locate(double t) const {
    const auto after = std::upper_bound(stamps_.begin(), stamps_.end(), t);
    size_t j = static_cast<size_t>(std::max<long>(0, after - stamps_.begin() - 1));
    j = std::min(j, stamps_.size() - 2);
    return {j, (t - stamps_[j]) / (stamps_[j + 1] - stamps_[j])};
  }

  std::vector<double> stamps_, heading_;
  std::vector<geometry::Pose2D> poses_;
};

double Huber(double r, double k) {
  const double a = std::abs(r);
  return a <= k ? 0.5 * a * a : k * (a - 0.5 * k);
}

// A pair of consecutive scans, first and first + 1, and the rotation their match found.
struct MatchedPair {
  size_t first;
  double rotation;
};

}  // namespace

std::vector<geometry::Pose2D> OdometryBefore(const std::vector<double>& stamps,
                                             const std::vector<geometry::Pose2D>& odometry,
                                             double latency_s) {
  CheckSizes(stamps, odometry.size());
  if (latency_s == 0.0 || odometry.size() < 2) return odometry;
  CheckIncreasing(stamps);
  const OdometryTrack track(stamps, odometry);
  std::vector<geometry::Pose2D> out;
  out.reserve(odometry.size());
  for (const double t : stamps) out.push_back(track.PoseAt(t - latency_s));
  return out;
}

ScanLatencyEstimate EstimateScanLatency(const std::vector<double>& stamps,
                                        const std::vector<geometry::Pose2D>& odometry,
                                        const std::vector<std::vector<Eigen::Vector2d>>& points,
                                        const ScanLatencyOptions& options,
                                        const ScanMatchOptions& match) {
  if (!(options.step_s > 0) || !(options.max_latency_s >= options.step_s) ||
      !(options.max_pairs >= 1) || !(options.rounds >= 1))
    throw std::invalid_argument(
        "scan latency: step_s must be > 0, max_latency_s >= step_s, max_pairs and rounds >= 1");
  CheckSizes(stamps, odometry.size());
  CheckIncreasing(stamps);
  if (stamps.size() < 2)
    throw std::invalid_argument("scan latency: a log of fewer than two scans does not tell it");
  if (points.size() != odometry.size())
    throw std::invalid_argument("scan latency: " + std::to_string(points.size()) + " scans for " +
                                std::to_string(odometry.size()) + " poses");
  const OdometryTrack track(stamps, odometry);
  // Odometry's rotation from scan i to i + 1, both sampled `latency` earlier.
  const auto rotation = [&](size_t i, double latency) {
    return track.HeadingAt(stamps[i + 1] - latency) - track.HeadingAt(stamps[i] - latency);
  };
  std::vector<size_t> telling;
  for (size_t i = 0; i + 1 < stamps.size(); ++i) {
    if (std::abs(rotation(i, options.max_latency_s) - rotation(i, -options.max_latency_s)) >=
        options.min_sensitivity_rad)
      telling.push_back(i);
  }
  if (telling.size() > static_cast<size_t>(options.max_pairs)) {
    std::vector<size_t> spread;
    for (int k = 0; k < options.max_pairs; ++k)
      spread.push_back(telling[static_cast<size_t>(k) * telling.size() /
                               static_cast<size_t>(options.max_pairs)]);
    telling = spread;
  }
  const int steps = static_cast<int>(std::round(options.max_latency_s / options.step_s));
  const auto rms = [&](const std::vector<MatchedPair>& pairs, double latency) {
    double sum = 0.0;
    for (const auto& p : pairs) {
      const double r = geometry::WrapAngle(p.rotation - rotation(p.first, latency));
      sum += r * r;
    }
    return std::sqrt(sum / static_cast<double>(pairs.size()));
  };
  ScanLatencyEstimate estimate;
  std::vector<MatchedPair> pairs;
  for (int round = 0; round < options.rounds; ++round) {
    pairs.clear();
    for (const size_t i : telling) {
      const ReferencePoints reference(points[i], match);
      const geometry::Pose2D guess =
          geometry::Between(track.PoseAt(stamps[i] - estimate.latency_s),
                            track.PoseAt(stamps[i + 1] - estimate.latency_s));
      const ScanMatch m = MatchScan(reference, points[i + 1], guess, match);
      if (m.inlier_share >= options.min_share && m.rms_m <= options.max_rms_m)
        pairs.push_back({i, m.pose.theta});
    }
    if (pairs.empty())
      throw std::invalid_argument(
          "scan latency: no pair of consecutive scans tells it (" + std::to_string(telling.size()) +
          " pairs turn faster or slower, none matched well): give the latency instead");
    double best_cost = INFINITY;
    for (int k = -steps; k <= steps; ++k) {
      const double latency = k * options.step_s;
      double cost = 0.0;
      for (const auto& p : pairs)
        cost +=
            Huber(geometry::WrapAngle(p.rotation - rotation(p.first, latency)), options.huber_rad);
      if (cost < best_cost) {
        best_cost = cost;
        estimate.latency_s = latency;
      }
    }
  }
  estimate.pairs = pairs.size();
  estimate.rms_at_zero_rad = rms(pairs, 0.0);
  estimate.rms_at_estimate_rad = rms(pairs, estimate.latency_s);
  return estimate;
}

}  // namespace structloc::slam_core
