// Merging scan segments into walls (see header).
#include "structloc/map_building/wall_merging.hpp"

#include <algorithm>
#include <cmath>

namespace structloc::map_building {
namespace {

using fitting::FitLine;
using fitting::LineEstimate;

Eigen::Vector2d Direction(const LineEstimate& fit) {
  return {-fit.sin_alpha, fit.cos_alpha};
}

// Distance between the intervals [a0, a1] and [b0, b1] (0 when they overlap).
double IntervalGap(double a0, double a1, double b0, double b1) {
  return std::max({0.0, b0 - a1, a0 - b1});
}

// The ends of a candidate's extent on its own fitted line (its extreme points
// may lie a few centimetres off the line).
std::pair<Eigen::Vector2d, Eigen::Vector2d> FittedEnds(const LineEstimate& fit,
                                                       const Eigen::Vector2d& low,
                                                       const Eigen::Vector2d& high) {
  const Eigen::Vector2d normal(fit.cos_alpha, fit.sin_alpha);
  return {low - (normal.dot(low) - fit.r) * normal, high - (normal.dot(high) - fit.r) * normal};
}

size_t DistinctScans(std::vector<uint32_t> scans) {
  std::sort(scans.begin(), scans.end());
  return static_cast<size_t>(std::unique(scans.begin(), scans.end()) - scans.begin());
}

}  // namespace

WallAccumulator::WallAccumulator(const WallMergeOptions& options) : options_(options) {}

bool WallAccumulator::Accepts(const Candidate& wall, const Eigen::Vector2d& first,
                              const Eigen::Vector2d& last, double& score) const {
  const Eigen::Vector2d d = last - first;
  const double length = d.norm();
  if (length <= 0.0) return false;
  const Eigen::Vector2d dir = Direction(wall.fit);
  // |sin| of the angle between the segment and the wall's line.
  if (std::abs(dir.x() * d.y() - dir.y() * d.x()) / length > std::sin(options_.max_angle_rad))
    return false;
  const double d0 = wall.fit.DistanceTo(first.x(), first.y());
  const double d1 = wall.fit.DistanceTo(last.x(), last.y());
  if (d0 > options_.max_offset_m || d1 > options_.max_offset_m) return false;
  const double s0 = dir.dot(first), s1 = dir.dot(last);
  const double w0 = dir.dot(wall.low), w1 = dir.dot(wall.high);
  if (IntervalGap(std::min(s0, s1), std::max(s0, s1), std::min(w0, w1), std::max(w0, w1)) >
      options_.max_extent_gap_m)
    return false;
  score = d0 + d1;
  return true;
}

void WallAccumulator::Absorb(Candidate& wall, const std::vector<Eigen::Vector2d>& points,
                             const std::vector<uint32_t>& scans) {
  if (wall.points.empty()) {
    wall.origin = points.front();
    wall.low = points.front();
    wall.high = points.front();
  }
  for (const auto& p : points) wall.sums.Add(p.x() - wall.origin.x(), p.y() - wall.origin.y());
  wall.fit = FitLine(wall.sums, wall.origin.x(), wall.origin.y());
  const Eigen::Vector2d dir = Direction(wall.fit);
  Eigen::Vector2d low = wall.low, high = wall.high;
  if (dir.dot(low) > dir.dot(high)) std::swap(low, high);
  for (const auto& p : {points.front(), points.back(), wall.low, wall.high}) {
    if (dir.dot(p) < dir.dot(low)) low = p;
    if (dir.dot(p) > dir.dot(high)) high = p;
  }
  wall.low = low;
  wall.high = high;
  wall.points.insert(wall.points.end(), points.begin(), points.end());
  wall.scans.insert(wall.scans.end(), scans.begin(), scans.end());
}

void WallAccumulator::Add(uint32_t scan, const Eigen::Vector2d& viewpoint,
                          const std::vector<Eigen::Vector2d>& points) {
  if (points.size() < 2) return;
  if (viewpoints_.size() <= scan) viewpoints_.resize(scan + 1, viewpoint);
  viewpoints_[scan] = viewpoint;
  ++segments_;
  Candidate* best = nullptr;
  double best_score = INFINITY;
  for (auto& wall : candidates_) {
    double score = 0.0;
    if (Accepts(wall, points.front(), points.back(), score) && score < best_score) {
      best = &wall;
      best_score = score;
    }
  }
  if (best == nullptr) {
    candidates_.emplace_back();
    best = &candidates_.back();
  }
  Absorb(*best, points, std::vector<uint32_t>(points.size(), scan));
}

void WallAccumulator::Keep(const std::vector<Eigen::Vector2d>& points,
                           const std::vector<uint32_t>& scans, std::vector<FittedWall>& out,
                           WallMergeReport& report) const {
  if (points.size() < 2) {
    ++report.too_few_points;
    return;
  }
  // Refit on the inliers, twice: the first fit may be pulled by a few stray points.
  std::vector<size_t> inliers(points.size());
  for (size_t i = 0; i < points.size(); ++i) inliers[i] = i;
  FittedWall fit = FitWall(points);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<size_t> kept;
    std::vector<Eigen::Vector2d> kept_points;
    const Eigen::Vector2d n(std::cos(fit.line.alpha), std::sin(fit.line.alpha));
    for (const size_t i : inliers) {
      if (std::abs(n.dot(points[i]) - fit.line.r) <= options_.inlier_distance_m) {
        kept.push_back(i);
        kept_points.push_back(points[i]);
      }
    }
    if (kept.size() < 2) {
      ++report.too_few_points;
      return;
    }
    inliers = std::move(kept);
    fit = FitWall(kept_points);
  }
  // Split at gaps, keeping each point's scan.
  std::vector<std::pair<double, size_t>> ordered;
  for (const size_t i : inliers) ordered.emplace_back(AlongWall(fit, points[i]), i);
  std::sort(ordered.begin(), ordered.end());
  size_t start = 0;
  for (size_t k = 1; k <= ordered.size(); ++k) {
    if (k < ordered.size() && ordered[k].first - ordered[k - 1].first <= options_.max_gap_m)
      continue;
    ++report.pieces;
    std::vector<Eigen::Vector2d> piece;
    std::vector<uint32_t> piece_scans;
    for (size_t m = start; m < k; ++m) {
      piece.push_back(points[ordered[m].second]);
      piece_scans.push_back(scans[ordered[m].second]);
    }
    start = k;
    if (static_cast<int>(piece.size()) < options_.min_points) {
      ++report.too_few_points;
      continue;
    }
    FittedWall wall = FitWall(piece);
    wall.sources = DistinctScans(piece_scans);
    Eigen::Vector2d viewpoint = Eigen::Vector2d::Zero();
    for (const uint32_t s : piece_scans) viewpoint += viewpoints_[s];
    wall.viewpoint = viewpoint / static_cast<double>(piece_scans.size());
    if (static_cast<int>(wall.sources) < options_.min_scans) {
      ++report.too_few_scans;
    } else if (wall.rms_m > options_.max_rms_m) {
      ++report.too_rough;
    } else if (wall.Length() < options_.min_length_m) {
      ++report.too_short;
    } else {
      out.push_back(wall);
    }
  }
}

std::vector<FittedWall> WallAccumulator::Walls(WallMergeReport& report) const {
  report = {};
  report.segments = segments_;
  report.candidates = candidates_.size();
  // Candidates that grew towards each other are one wall: merge until stable.
  std::vector<Candidate> walls = candidates_;
  std::sort(walls.begin(), walls.end(), [](const Candidate& a, const Candidate& b) {
    return a.points.size() > b.points.size();
  });
  std::vector<bool> gone(walls.size(), false);
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < walls.size(); ++i) {
      if (gone[i]) continue;
      for (size_t j = i + 1; j < walls.size(); ++j) {
        double score = 0.0;
        if (gone[j]) continue;
        const auto ends = FittedEnds(walls[j].fit, walls[j].low, walls[j].high);
        if (!Accepts(walls[i], ends.first, ends.second, score)) continue;
        Absorb(walls[i], walls[j].points, walls[j].scans);
        gone[j] = true;
        ++report.merged;
        changed = true;
      }
    }
  }
  std::vector<FittedWall> out;
  for (size_t i = 0; i < walls.size(); ++i) {
    if (!gone[i]) Keep(walls[i].points, walls[i].scans, out, report);
  }
  return out;
}

}  // namespace structloc::map_building
