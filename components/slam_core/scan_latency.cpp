// A recording's scan latency against its odometry (see header).
#include "structloc/slam_core/scan_latency.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

#include "parallel_for.hpp"

namespace structloc::slam_core {
namespace {

void CheckSizes(const std::vector<double>& stamps, size_t poses) {
  if (stamps.size() != poses)
    throw std::invalid_argument("scan latency: " + std::to_string(stamps.size()) + " stamps for " +
                                std::to_string(poses) + " poses");
}

// Empty when `stamps` increase; else names the first that does not.
std::string NotIncreasing(const std::vector<double>& stamps) {
  for (size_t i = 1; i < stamps.size(); ++i) {
    if (!(stamps[i] > stamps[i - 1]))
      return "scan " + std::to_string(i) + "'s stamp " + std::to_string(stamps[i]) +
             " is not after the one before (" + std::to_string(stamps[i - 1]) +
             "); a latency needs increasing stamps (re-stamp the log)";
  }
  return {};
}

// Odometry as a function of time: linear between its samples, made
// continuous in heading (no jumps of 2 pi) so that rotations over any time
// come out whole. A sample that repeats the one before exactly is left out
// (but the log's last): odometry that was not updated, because the robot
// stood still or because its messages stalled, as MIT CSAIL's do for 0.8 s
// before a single 85 deg step; its motion is then spread over the stall
// instead of put into the last interval. So is a sample stamped no later
// than the one kept before it (the callers that need increasing stamps
// refuse others first).
class OdometryTrack {
 public:
  OdometryTrack(const std::vector<double>& stamps, const std::vector<geometry::Pose2D>& odometry) {
    for (size_t i = 0; i < odometry.size(); ++i) {
      const bool repeat = i > 0 && odometry[i].x == odometry[i - 1].x &&
                          odometry[i].y == odometry[i - 1].y &&
                          odometry[i].theta == odometry[i - 1].theta;
      if (repeat && i + 1 < odometry.size()) continue;
      if (!stamps_.empty() && !(stamps[i] > stamps_.back())) continue;
      heading_.push_back(poses_.empty()
                             ? odometry[i].theta
                             : heading_.back() +
                                   geometry::WrapAngle(odometry[i].theta - poses_.back().theta));
      stamps_.push_back(stamps[i]);
      poses_.push_back(odometry[i]);
    }
  }

  // Whether it holds two samples or more (else it tells no motion).
  bool Moves() const { return stamps_.size() >= 2; }

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

// Scan `points`, whose first beam was taken at `taken`, moved into the laser's
// frame then, each point by the motion to `times` later.
std::vector<Eigen::Vector2d> Deskewed(const OdometryTrack& track, double taken,
                                      const std::vector<Eigen::Vector2d>& points,
                                      const std::vector<double>& times) {
  if (times.empty()) return points;
  const geometry::Pose2D first = track.PoseAt(taken);
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (size_t j = 0; j < points.size(); ++j)
    out.push_back(geometry::Between(first, track.PoseAt(taken + times[j])).Apply(points[j]));
  return out;
}

void CheckTimes(const std::vector<std::vector<Eigen::Vector2d>>& points, const PointTimes& times) {
  if (times.empty()) return;
  bool fit = times.size() == points.size();
  for (size_t i = 0; fit && i < times.size(); ++i)
    fit = times[i].empty() || times[i].size() == points[i].size();
  if (!fit)
    throw std::invalid_argument("scan latency: the points' times do not fit the scans' points");
}

// Each matched pair's robust cost at each latency of the grid.
using LatencyCosts = std::vector<std::vector<double>>;

// The grid index whose cost summed over pairs `rows` is least.
size_t Best(const LatencyCosts& costs, const std::vector<size_t>& rows) {
  std::vector<double> sum(costs.front().size(), 0.0);
  for (const size_t r : rows) {
    for (size_t k = 0; k < sum.size(); ++k) sum[k] += costs[r][k];
  }
  return static_cast<size_t>(std::min_element(sum.begin(), sum.end()) - sum.begin());
}

// The interval (grid indices) holding the estimate at the options' confidence:
// the pairs resampled in blocks of consecutive ones, with replacement, the
// estimate found again on each resampling, and the percentiles of those
// estimates (a moving-block bootstrap, Kuensch 1989).
std::pair<size_t, size_t> BootstrapInterval(const LatencyCosts& costs,
                                            const ScanLatencyOptions& options) {
  const size_t n = costs.size();
  const size_t block = std::min(n, static_cast<size_t>(options.block_pairs));
  std::mt19937 rng(options.seed);
  std::uniform_int_distribution<size_t> start(0, n - block);
  std::vector<size_t> estimates, rows;
  for (int b = 0; b < options.resamples; ++b) {
    rows.clear();
    while (rows.size() < n) {
      const size_t s = start(rng);
      for (size_t r = s; r < s + block && rows.size() < n; ++r) rows.push_back(r);
    }
    estimates.push_back(Best(costs, rows));
  }
  std::sort(estimates.begin(), estimates.end());
  const double tail = 0.5 * (1.0 - options.confidence) * static_cast<double>(estimates.size());
  const size_t low = std::min(estimates.size() - 1, static_cast<size_t>(std::floor(tail)));
  const size_t high = estimates.size() - 1 - low;
  return {estimates[low], estimates[high]};
}

}  // namespace

void ScanLatencyOptions::Validate() const {
  if (!(step_s > 0)) throw std::invalid_argument("scan_latency: step_s must be > 0");
  if (!(max_latency_s >= step_s))
    throw std::invalid_argument("scan_latency: max_latency_s must be >= step_s");
  if (!(rounds >= 1) || !(max_rounds >= rounds))
    throw std::invalid_argument("scan_latency: rounds must be >= 1, max_rounds >= rounds");
  if (!(confidence > 0) || !(confidence < 1))
    throw std::invalid_argument("scan_latency: confidence must be within (0, 1)");
  if (!(max_pairs >= 1) || !(resamples >= 1) || !(block_pairs >= 1))
    throw std::invalid_argument("scan_latency: max_pairs, resamples and block_pairs must be >= 1");
}

std::vector<geometry::Pose2D> OdometryBefore(const std::vector<double>& stamps,
                                             const std::vector<geometry::Pose2D>& odometry,
                                             double latency_s) {
  CheckSizes(stamps, odometry.size());
  if (latency_s == 0.0 || odometry.size() < 2) return odometry;
  if (const std::string why = NotIncreasing(stamps); !why.empty())
    throw std::invalid_argument("scan latency: " + why);
  const OdometryTrack track(stamps, odometry);
  std::vector<geometry::Pose2D> out;
  out.reserve(odometry.size());
  for (const double t : stamps) out.push_back(track.PoseAt(t - latency_s));
  return out;
}

std::vector<std::vector<Eigen::Vector2d>> DeskewedPoints(
    const std::vector<double>& stamps, const std::vector<geometry::Pose2D>& odometry,
    std::vector<std::vector<Eigen::Vector2d>> points, const PointTimes& point_times,
    double latency_s) {
  CheckSizes(stamps, odometry.size());
  CheckTimes(points, point_times);
  if (point_times.empty()) return points;
  const OdometryTrack track(stamps, odometry);
  if (!track.Moves()) return points;
  for (size_t i = 0; i < points.size(); ++i)
    points[i] = Deskewed(track, stamps[i] - latency_s, points[i], point_times[i]);
  return points;
}

ScanLatencyEstimate EstimateScanLatency(const std::vector<double>& stamps,
                                        const std::vector<geometry::Pose2D>& odometry,
                                        const std::vector<std::vector<Eigen::Vector2d>>& points,
                                        const ScanLatencyOptions& options,
                                        const ScanMatchOptions& match,
                                        const PointTimes& point_times, int threads) {
  options.Validate();
  CheckSizes(stamps, odometry.size());
  if (points.size() != odometry.size())
    throw std::invalid_argument("scan latency: " + std::to_string(points.size()) + " scans for " +
                                std::to_string(odometry.size()) + " poses");
  CheckTimes(points, point_times);
  ScanLatencyEstimate estimate;
  estimate.untold = NotIncreasing(stamps);
  if (stamps.size() < 2) estimate.untold = "a log of fewer than two scans does not tell it";
  if (!estimate.untold.empty()) return estimate;
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
  std::vector<MatchedPair> pairs;
  LatencyCosts costs;
  const auto at = [&](size_t i, double latency) {
    return point_times.empty() ? points[i]
                               : Deskewed(track, stamps[i] - latency, points[i], point_times[i]);
  };
  double moved = INFINITY;  // by the last round
  for (int round = 0;
       round < options.rounds ||
       (!point_times.empty() && round < options.max_rounds && moved > 0.5 * options.step_s);
       ++round) {
    const double from = estimate.latency_s;
    std::vector<ScanMatch> matches(telling.size());
    ParallelFor(telling.size(), threads, [&](size_t t, size_t) {
      const size_t i = telling[t];
      const ReferencePoints reference(at(i, from), match);
      const geometry::Pose2D guess =
          geometry::Between(track.PoseAt(stamps[i] - from), track.PoseAt(stamps[i + 1] - from));
      matches[t] = MatchScan(reference, at(i + 1, from), guess, match);
    });
    pairs.clear();
    for (size_t t = 0; t < telling.size(); ++t) {
      const ScanMatch& m = matches[t];
      if (m.inlier_share >= options.min_share && m.rms_m <= options.max_rms_m)
        pairs.push_back({telling[t], m.pose.theta});
    }
    if (pairs.empty()) {
      estimate = {};
      estimate.untold = "no turn that speeds up or slows down matched well (" +
                        std::to_string(telling.size()) + " pairs of consecutive scans tried)";
      return estimate;
    }
    costs.assign(pairs.size(), std::vector<double>(static_cast<size_t>(2 * steps + 1)));
    for (size_t p = 0; p < pairs.size(); ++p) {
      for (int k = -steps; k <= steps; ++k)
        costs[p][static_cast<size_t>(k + steps)] = Huber(
            geometry::WrapAngle(pairs[p].rotation - rotation(pairs[p].first, k * options.step_s)),
            options.huber_rad);
    }
    std::vector<size_t> all(pairs.size());
    std::iota(all.begin(), all.end(), size_t{0});
    estimate.latency_s = (static_cast<int>(Best(costs, all)) - steps) * options.step_s;
    moved = std::abs(estimate.latency_s - from);
  }
  const auto [low, high] = BootstrapInterval(costs, options);
  estimate.interval_low_s = (static_cast<int>(low) - steps) * options.step_s;
  estimate.interval_high_s = (static_cast<int>(high) - steps) * options.step_s;
  estimate.pairs = pairs.size();
  estimate.rms_at_zero_rad = rms(pairs, 0.0);
  estimate.rms_at_estimate_rad = rms(pairs, estimate.latency_s);
  return estimate;
}

}  // namespace structloc::slam_core
