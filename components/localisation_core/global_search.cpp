// The search of the global localiser (see global_localiser.hpp): the coarse
// lattice of positions and headings on the blurred field, the refinement of
// the best candidates on the fine field, the polishing and ranking of the
// distinct poses, and the decision "found", "ambiguous" or "not found".
#include "structloc/localisation_core/global_localiser.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace structloc::localisation_core {
namespace {

bool Distinct(const geometry::Pose2D& a, const geometry::Pose2D& b,
              const GlobalLocaliserOptions& o) {
  return std::hypot(a.x - b.x, a.y - b.y) > o.distinct_distance_m ||
         std::abs(geometry::WrapAngle(a.theta - b.theta)) > o.distinct_heading_rad;
}

struct CoarseHit {
  float score;
  int position;
  int heading;
};

}  // namespace

GlobalResult GlobalLocaliser::Locate(const std::vector<Eigen::Vector2d>& points,
                                     const SearchWindow* window) const {
  return Locate(OneScan(points), window);
}

GlobalResult GlobalLocaliser::Locate(const Readings& readings, const SearchWindow* window) const {
  GlobalResult result;
  result.scans = readings.scans;
  const Readings usable = UsableReadings(readings);
  const std::vector<Eigen::Vector2d>& all = usable.points;
  const std::vector<Eigen::Vector2d> points = Spread(all, options_.max_points);
  result.points_used = all.size();
  if (all.size() < static_cast<size_t>(options_.min_points)) {
    result.reason = "only " + std::to_string(all.size()) + " readings within " +
                    std::to_string(options_.min_range_m) + ".." +
                    std::to_string(options_.max_range_m) + " m";
    return result;
  }
  // With earlier scans, the newest scan's own readings: it must have enough.
  const bool earlier = readings.newest_points && *readings.newest_points < readings.points.size();
  Readings newest;
  if (earlier) {
    const auto end = readings.points.begin() + static_cast<std::ptrdiff_t>(*readings.newest_points);
    newest = UsableReadings(OneScan({readings.points.begin(), end}));
    if (newest.points.size() < static_cast<size_t>(options_.min_points)) {
      result.reason = "the newest scan has only " + std::to_string(newest.points.size()) +
                      " readings within " + std::to_string(options_.min_range_m) + ".." +
                      std::to_string(options_.max_range_m) + " m";
      return result;
    }
  }
  const std::vector<Eigen::Vector2d> coarse = Spread(points, options_.coarse_points);

  // Coarse search: every candidate position at every heading, scan points
  // looked up in the blurred field.
  const double res = options_.grid_resolution_m;
  const int headings = std::max(
      1, static_cast<int>(std::ceil(2 * geometry::kPi / options_.coarse_heading_step_rad)));
  const double heading_step = 2 * geometry::kPi / headings;
  std::vector<float> offsets;  // per heading, per point: x, y in cells
  offsets.reserve(static_cast<size_t>(headings) * coarse.size() * 2);
  for (int h = 0; h < headings; ++h) {
    const double c = std::cos(h * heading_step), s = std::sin(h * heading_step);
    for (const auto& p : coarse) {
      offsets.push_back(static_cast<float>((c * p.x() - s * p.y()) / res));
      offsets.push_back(static_cast<float>((s * p.x() + c * p.y()) / res));
    }
  }
  const int separation =
      std::max(1, static_cast<int>(std::ceil(options_.distinct_heading_rad * 2 / heading_step)));
  std::vector<CoarseHit> hits;
  hits.reserve(positions_.size() * 2);
  std::vector<float> scores(static_cast<size_t>(headings));
  const size_t n = coarse.size();
  // A lattice position half a lattice diagonal outside the window can still
  // be the one nearest a pose inside it.
  const double reach =
      window != nullptr ? window->radius_m + options_.coarse_step_m * std::sqrt(0.5) : 0.0;
  for (size_t k = 0; k < positions_.size(); ++k) {
    if (window != nullptr && (positions_[k] - window->centre.Translation()).norm() > reach) {
      continue;
    }
    const float px = static_cast<float>((positions_[k].x() - cells_.x0) / res);
    const float py = static_cast<float>((positions_[k].y() - cells_.y0) / res);
    for (int h = 0; h < headings; ++h) {
      scores[static_cast<size_t>(h)] = -1.0f;  // outside the window: never the best
      if (window != nullptr &&
          std::abs(geometry::WrapAngle(h * heading_step - window->centre.theta)) >
              window->heading_rad + 0.5 * heading_step) {
        continue;
      }
      const float* o = &offsets[static_cast<size_t>(h) * n * 2];
      float sum = 0.0f;
      for (size_t i = 0; i < n; ++i) {
        const float fc = px + o[2 * i], fr = py + o[2 * i + 1];
        if (!(fc >= 0.0f && fr >= 0.0f)) continue;  // off the grid (not truncated onto it)
        const int c = static_cast<int>(fc), r = static_cast<int>(fr);
        if (c < cells_.width && r < cells_.height)
          sum += coarse_gain_[static_cast<size_t>(r) * cells_.width + c];
      }
      scores[static_cast<size_t>(h)] = sum;
    }
    // The best heading here, and the best one clearly turned from it.
    const int best =
        static_cast<int>(std::max_element(scores.begin(), scores.end()) - scores.begin());
    int second = -1;
    for (int h = 0; h < headings; ++h) {
      const int apart = std::min(std::abs(h - best), headings - std::abs(h - best));
      if (apart >= separation && (second < 0 || scores[h] > scores[second])) second = h;
    }
    hits.push_back({scores[best], static_cast<int>(k), best});
    if (second >= 0 && scores[second] >= 0.0f)
      hits.push_back({scores[second], static_cast<int>(k), second});
  }
  const size_t keep = std::min(hits.size(), static_cast<size_t>(options_.coarse_keep));
  std::partial_sort(hits.begin(), hits.begin() + keep, hits.end(),
                    [](const CoarseHit& a, const CoarseHit& b) { return a.score > b.score; });

  // Refinement on the fine field; poses that converged to the same place
  // count once.
  auto by_score = [](const GlobalCandidate& a, const GlobalCandidate& b) {
    return a.score > b.score;
  };
  std::vector<GlobalCandidate> converged;
  for (size_t i = 0; i < keep; ++i) {
    const auto& hit = hits[i];
    const geometry::Pose2D start{positions_[hit.position].x(), positions_[hit.position].y(),
                                 geometry::WrapAngle(hit.heading * heading_step)};
    const geometry::Pose2D pose = Refine(fine_gain_, points, start, 0.5 * options_.coarse_step_m,
                                         0.5 * options_.coarse_heading_step_rad);
    if (window != nullptr && !InWindow(pose, *window)) continue;  // climbed out of it
    converged.push_back({pose, FineScore(fine_gain_, points, pose), std::nullopt});
  }
  std::sort(converged.begin(), converged.end(), by_score);
  std::vector<GlobalCandidate> refined;
  for (const auto& candidate : converged) {
    if (refined.size() >= static_cast<size_t>(options_.ranked)) break;
    bool seen = false;
    for (const auto& r : refined) {
      seen = seen || (std::hypot(r.pose.x - candidate.pose.x, r.pose.y - candidate.pose.y) < 0.1 &&
                      std::abs(geometry::WrapAngle(r.pose.theta - candidate.pose.theta)) < 0.035);
    }
    if (!seen) refined.push_back(candidate);
  }
  // The best pose distinct from the best one must be ranked too, however many
  // near-duplicates of the best outscored it in the refinement: without it a
  // symmetric twin would never be weighed and the best would look unrivalled.
  if (!refined.empty()) {
    const bool rivalled = std::any_of(refined.begin() + 1, refined.end(), [&](const auto& r) {
      return Distinct(r.pose, refined.front().pose, options_);
    });
    if (!rivalled) {
      const auto twin = std::find_if(converged.begin(), converged.end(), [&](const auto& c) {
        return Distinct(c.pose, refined.front().pose, options_);
      });
      if (twin != converged.end()) refined.push_back(*twin);
    }
  }
  // Polishing on the sharp field with all points, and ranking.
  for (auto& candidate : refined) {
    candidate.pose = Refine(rank_gain_, all, candidate.pose, 0.05, 0.01);
    candidate.score = window != nullptr && !InWindow(candidate.pose, *window)
                          ? 0.0
                          : RankScore(all, usable.seen_from, candidate.pose);
  }
  std::sort(refined.begin(), refined.end(), by_score);
  if (refined.empty()) {
    result.reason = std::string(window != nullptr ? "the search window has" : "the map has") +
                    " no place clear of walls by " + std::to_string(options_.clearance_m) + " m";
    return result;
  }
  // With earlier scans, how much of the newest scan alone a pose explains
  // (asked only of the best and of the poses close to it on all readings).
  auto newest_share = [&](GlobalCandidate& c) {
    if (!c.newest_score) c.newest_score = RankScore(newest.points, {}, c.pose);
    return *c.newest_score;
  };
  const double margin = options_.ambiguity_margin;
  if (earlier) newest_share(refined.front());
  bool ambiguous = false;
  std::optional<size_t> rival;
  for (size_t i = 1; i < refined.size() && !ambiguous; ++i) {
    if (!Distinct(refined[i].pose, refined.front().pose, options_)) continue;
    ambiguous = refined[i].score > refined.front().score - margin &&
                (!earlier || newest_share(refined[i]) > *refined.front().newest_score - margin);
    if (!rival || ambiguous) rival = i;
  }
  result.best = refined.front();
  if (rival) result.runner_up = refined[*rival];
  const auto too_little = [&](double share, const char* of) {
    return "the best pose explains only " + std::to_string(static_cast<int>(100 * share)) +
           " % of " + of + " (at least " +
           std::to_string(static_cast<int>(100 * options_.min_score)) + " % needed)";
  };
  if (result.best->score < options_.min_score) {
    result.decision = GlobalDecision::kNotFound;
    result.reason = too_little(result.best->score, earlier ? "the readings" : "the scan");
  } else if (earlier && *result.best->newest_score < options_.min_score) {
    result.decision = GlobalDecision::kNotFound;
    result.reason = too_little(*result.best->newest_score, "the newest scan alone");
  } else if (ambiguous) {
    result.decision = GlobalDecision::kAmbiguous;
    result.reason = earlier
                        ? "a distinct pose explains the scan and the ones before it nearly as well"
                        : "a distinct pose explains the scan nearly as well";
  } else {
    result.decision = GlobalDecision::kFound;
  }
  return result;
}

}  // namespace structloc::localisation_core
