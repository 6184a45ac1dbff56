// The search of the global localiser (see global_localiser.hpp), as a
// GlobalSearch done a slice at a time: the coarse lattice of positions and
// headings on the blurred field (global_coarse_search.cpp), the refinement
// of the best candidates on the fine field, the polishing and ranking of the
// distinct poses, and the decision "found", "ambiguous" or "not found".
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "structloc/localisation_core/global/global_localiser.hpp"

namespace structloc::localisation_core {

bool Distinct(const geometry::Pose2D& a, const geometry::Pose2D& b,
              const GlobalLocaliserOptions& o) {
  return std::hypot(a.x - b.x, a.y - b.y) > o.distinct_distance_m ||
         std::abs(geometry::WrapAngle(a.theta - b.theta)) > o.distinct_heading_rad;
}

namespace {

// A point checked for a beam through a wall (RankScore) costs about ten
// lookups in a field.
constexpr uint64_t kRankPointWork = 10;

int Headings(const GlobalLocaliserOptions& o) {
  return std::max(1, static_cast<int>(std::ceil(2 * geometry::kPi / o.coarse_heading_step_rad)));
}

}  // namespace

GlobalResult GlobalLocaliser::Locate(const std::vector<Eigen::Vector2d>& points,
                                     const SearchWindow* window) const {
  return Locate(OneScan(points), window);
}

GlobalResult GlobalLocaliser::Locate(const Readings& readings, const SearchWindow* window) const {
  GlobalSearch search(*this, readings,
                      window != nullptr ? std::optional<SearchWindow>(*window) : std::nullopt);
  search.Advance(std::numeric_limits<uint64_t>::max());
  return search.Result();
}

uint64_t GlobalSearch::CoarseWork(const GlobalLocaliserOptions& options, size_t positions) {
  return static_cast<uint64_t>(positions) * static_cast<uint64_t>(Headings(options)) *
         static_cast<uint64_t>(options.coarse_points);
}

GlobalSearch::GlobalSearch(const GlobalLocaliser& localiser, const Readings& readings,
                           std::optional<SearchWindow> window)
    : g_(localiser), window_(window) {
  const auto& o = g_.options_;
  result_.scans = readings.scans;
  usable_ = g_.UsableReadings(readings);
  const std::vector<Eigen::Vector2d>& all = usable_.points;
  points_ = GlobalLocaliser::Spread(all, o.max_points);
  result_.points_used = all.size();
  phase_ = Phase::kDone;
  if (all.size() < static_cast<size_t>(o.min_points)) {
    result_.reason = "only " + std::to_string(all.size()) + " readings within " +
                     std::to_string(o.min_range_m) + ".." + std::to_string(o.max_range_m) + " m";
    return;
  }
  // With earlier scans, the newest scan's own readings: it must have enough.
  earlier_ = readings.newest_points && *readings.newest_points < readings.points.size();
  if (earlier_) {
    const auto end = readings.points.begin() + static_cast<std::ptrdiff_t>(*readings.newest_points);
    newest_ = g_.UsableReadings(OneScan({readings.points.begin(), end}));
    if (newest_.points.size() < static_cast<size_t>(o.min_points)) {
      result_.reason = "the newest scan has only " + std::to_string(newest_.points.size()) +
                       " readings within " + std::to_string(o.min_range_m) + ".." +
                       std::to_string(o.max_range_m) + " m";
      return;
    }
  }
  phase_ = Phase::kCoarse;
  const std::vector<Eigen::Vector2d> coarse = GlobalLocaliser::Spread(points_, o.coarse_points);
  coarse_count_ = coarse.size();
  // Every candidate position at every heading, scan points looked up in the
  // blurred field, offsets precomputed per heading.
  const double res = o.grid_resolution_m;
  headings_ = Headings(o);
  heading_step_ = 2 * geometry::kPi / headings_;
  offsets_.reserve(static_cast<size_t>(headings_) * coarse.size() * 2);
  for (int h = 0; h < headings_; ++h) {
    const double c = std::cos(h * heading_step_), s = std::sin(h * heading_step_);
    for (const auto& p : coarse) {
      offsets_.push_back(static_cast<int>(std::floor((c * p.x() - s * p.y()) / res)));
      offsets_.push_back(static_cast<int>(std::floor((s * p.x() + c * p.y()) / res)));
    }
  }
  work_ += offsets_.size();
  for (const auto& gains : g_.phase_gains_) {
    auto& prepared = phase_offsets_.emplace_back();
    prepared.reserve(offsets_.size() / 2);
    for (size_t i = 0; i + 1 < offsets_.size(); i += 2)
      prepared.push_back(gains.Prepare(offsets_[i], offsets_[i + 1]));
  }
  separation_ =
      std::max(1, static_cast<int>(std::ceil(o.distinct_heading_rad * 2 / heading_step_)));
  // A lattice position half a lattice diagonal outside the window can still
  // be the one nearest a pose inside it.
  if (window_) {
    window_positions_ = g_.PositionsNear(window_->centre.Translation(),
                                         window_->radius_m + o.coarse_step_m * std::sqrt(0.5));
    work_ += window_positions_.size();
  }
  // The headings a position is scored at: in a window, those within it.
  for (int h = 0; h < headings_; ++h) {
    if (window_ && std::abs(geometry::WrapAngle(h * heading_step_ - window_->centre.theta)) >
                       window_->heading_rad + 0.5 * heading_step_) {
      continue;
    }
    scored_headings_.push_back(static_cast<uint16_t>(h));
  }
  hits_.reserve(window_ ? 64 : static_cast<size_t>(o.coarse_keep) * 2);
  kept_scores_.reserve(static_cast<size_t>(o.coarse_keep));
  scores_.resize(static_cast<size_t>(headings_));
  for (auto& scores : block_scores_) scores.resize(static_cast<size_t>(headings_));
  for (auto& bounds : quarter_bounds_) bounds.resize(static_cast<size_t>(headings_));
}

bool GlobalSearch::Advance(uint64_t work) {
  const uint64_t until = work > std::numeric_limits<uint64_t>::max() - work_
                             ? std::numeric_limits<uint64_t>::max()
                             : work_ + work;
  do {
    switch (phase_) {
      case Phase::kCoarse:
        CoarseStep();
        break;
      case Phase::kRefine:
        if (next_ < keep_) {
          if (RefineHit(next_)) ++next_;
        } else {
          ChooseRanked();
        }
        break;
      case Phase::kRank:
        if (next_ < refined_.size()) {
          if (RankCandidate(next_)) ++next_;
        } else {
          Decide();
        }
        break;
      case Phase::kDone:
        return true;
    }
  } while (work_ < until && phase_ != Phase::kDone);
  result_.work = work_;
  return Done();
}

void GlobalSearch::SelectHits() {
  const size_t keep = static_cast<size_t>(g_.options_.coarse_keep);
  keep_ = std::min(hits_.size(), keep);
  if (keep_ > 0 && keep_ < hits_.size()) {
    const auto last = hits_.begin() + static_cast<std::ptrdiff_t>(keep_ - 1);
    std::nth_element(hits_.begin(), last, hits_.end(),
                     [](const CoarseHit& a, const CoarseHit& b) { return a.score > b.score; });
    // Every hit scoring as well as the last one kept is kept too: which of
    // equal hits (a corridor that repeats every few lattice steps scores the
    // same at each repetition) were kept would otherwise depend on the order
    // in which they were found, and a twin left out makes its rival look
    // unrivalled. Not where the last one kept explains nothing (a scan of
    // clutter ties everywhere at 0), and never more than twice coarse_keep.
    const float least = last->score;
    if (least > 0.0f) {
      const auto tied_end = std::partition(
          last + 1, hits_.end(), [least](const CoarseHit& h) { return h.score >= least; });
      keep_ = std::min(static_cast<size_t>(tied_end - hits_.begin()), 2 * keep);
    }
  }
  KeepLocalMaxima();
  // Refined by heading and position (whatever order the coarse phase found
  // them in), so that neighbouring climbs look up neighbouring cells, still
  // in the cache.
  std::sort(hits_.begin(), hits_.begin() + static_cast<std::ptrdiff_t>(keep_),
            [](const CoarseHit& a, const CoarseHit& b) {
              return a.heading != b.heading ? a.heading < b.heading : a.position < b.position;
            });
  work_ += hits_.size();
  phase_ = Phase::kRefine;
  next_ = 0;
}

// Non-maximum suppression: only the local maxima of the coarse score are
// refined. A kept hit is dropped when a kept hit at its own or a neighbouring
// lattice position (one coarse step in x, y or both), turned at most one
// coarse heading step from it and not a distinct place from it, scores more
// (of equal ones the first in position and heading order stays). The better
// neighbour may be dropped in turn, so a dropped hit's climb is not always
// replaced by one started next to it; what is refined is every peak of the
// coarse score, and each place whose score peaks is climbed from its peak.
// Climbs from neighbouring hits start at most a lattice step and a heading
// step apart, which their first moves (half of each) cover: in the pillared
// hall the 3000 hits kept climbed to about 600 distinct poses, and about 600
// local maxima remain. With the default options neighbours are never
// distinct places (0.35 m and 1.5 deg apart at most).
void GlobalSearch::KeepLocalMaxima() {
  const auto kept_end = hits_.begin() + static_cast<std::ptrdiff_t>(keep_);
  auto by_place = [](const CoarseHit& a, const CoarseHit& b) {
    return a.position != b.position ? a.position < b.position : a.heading < b.heading;
  };
  std::sort(hits_.begin(), kept_end, by_place);
  const auto& lattice = g_.lattice_;
  const double step = g_.options_.coarse_step_m;
  auto pose = [&](const CoarseHit& h) {
    const Eigen::Vector2d& at = g_.positions_[static_cast<size_t>(h.position)];
    return geometry::Pose2D{at.x(), at.y(), geometry::WrapAngle(h.heading * heading_step_)};
  };
  dropped_.assign(keep_, 0);
  for (size_t i = 0; i < keep_; ++i) {
    const CoarseHit& hit = hits_[i];
    const Eigen::Vector2d& at = g_.positions_[static_cast<size_t>(hit.position)];
    const int column = static_cast<int>(std::lround((at.x() - lattice.x0) / step));
    const int row = static_cast<int>(std::lround((at.y() - lattice.y0) / step));
    for (int r = std::max(0, row - 1); r <= std::min(lattice.rows - 1, row + 1); ++r) {
      for (int c = std::max(0, column - 1); c <= std::min(lattice.columns - 1, column + 1); ++c) {
        const int k = lattice.position[static_cast<size_t>(r) * lattice.columns + c];
        if (k < 0) continue;
        const auto [first, last] = std::equal_range(
            hits_.begin(), kept_end, CoarseHit{0.0f, k, 0},
            [](const CoarseHit& a, const CoarseHit& b) { return a.position < b.position; });
        for (auto other = first; other != last; ++other) {
          const auto j = static_cast<size_t>(other - hits_.begin());
          const int apart = std::abs(other->heading - hit.heading);
          const bool near = std::min(apart, headings_ - apart) <= 1;
          const bool better = other->score > hit.score || (other->score == hit.score && j < i);
          if (j != i && near && better && !Distinct(pose(*other), pose(hit), g_.options_))
            dropped_[i] = 1;
        }
      }
    }
  }
  work_ += 9 * keep_;  // a look at each neighbour of each hit
  size_t kept = 0;
  for (size_t i = 0; i < keep_; ++i) {
    if (!dropped_[i]) hits_[kept++] = hits_[i];
  }
  keep_ = kept;
}

// Refinement on the fine field, a round of the climb at a time.
bool GlobalSearch::RefineHit(size_t i) {
  const auto& o = g_.options_;
  if (!climb_) {
    const auto& hit = hits_[i];
    const geometry::Pose2D start{g_.positions_[hit.position].x(), g_.positions_[hit.position].y(),
                                 geometry::WrapAngle(hit.heading * heading_step_)};
    climb_ = g_.StartClimb(g_.fine_gain_, points_, start, 0.5 * o.coarse_step_m,
                           0.5 * o.coarse_heading_step_rad, o.refine_precision_m, &work_);
    return false;
  }
  if (!climb_->Done()) {
    g_.ClimbRound(g_.fine_gain_, points_, *climb_, &work_);
    return false;
  }
  const geometry::Pose2D pose = climb_->pose;
  const double score = climb_->score;
  climb_.reset();
  if (window_ && !g_.InWindow(pose, *window_)) return true;  // climbed out of it
  converged_.push_back({pose, score, std::nullopt});
  return true;
}

// Poses that converged to the same place count once; the best distinct ones
// go on to be ranked.
void GlobalSearch::ChooseRanked() {
  const auto& o = g_.options_;
  auto by_score = [](const GlobalCandidate& a, const GlobalCandidate& b) {
    return a.score > b.score;
  };
  std::sort(converged_.begin(), converged_.end(), by_score);
  for (const auto& candidate : converged_) {
    if (refined_.size() >= static_cast<size_t>(o.ranked)) break;
    bool seen = false;
    for (const auto& r : refined_) {
      seen = seen || (std::hypot(r.pose.x - candidate.pose.x, r.pose.y - candidate.pose.y) < 0.1 &&
                      std::abs(geometry::WrapAngle(r.pose.theta - candidate.pose.theta)) < 0.035);
    }
    if (!seen) refined_.push_back(candidate);
  }
  // The best pose distinct from the best one must be ranked too, however many
  // near-duplicates of the best outscored it in the refinement: without it a
  // symmetric twin would never be weighed and the best would look unrivalled.
  if (!refined_.empty()) {
    const bool rivalled = std::any_of(refined_.begin() + 1, refined_.end(), [&](const auto& r) {
      return Distinct(r.pose, refined_.front().pose, o);
    });
    if (!rivalled) {
      const auto twin = std::find_if(converged_.begin(), converged_.end(), [&](const auto& c) {
        return Distinct(c.pose, refined_.front().pose, o);
      });
      if (twin != converged_.end()) refined_.push_back(*twin);
    }
  }
  work_ += converged_.size();
  phase_ = Phase::kRank;
  next_ = 0;
}

// Polishing on the sharp field with all points, a round at a time, and ranking.
bool GlobalSearch::RankCandidate(size_t i) {
  auto& candidate = refined_[i];
  if (!climb_) {
    climb_ = g_.StartClimb(g_.rank_gain_, usable_.points, candidate.pose, 0.05, 0.01,
                           GlobalLocaliser::kPolishPrecisionM, &work_);
    return false;
  }
  if (!climb_->Done()) {
    g_.ClimbRound(g_.rank_gain_, usable_.points, *climb_, &work_);
    return false;
  }
  candidate.pose = climb_->pose;
  climb_.reset();
  candidate.score = window_ && !g_.InWindow(candidate.pose, *window_)
                        ? 0.0
                        : g_.RankScore(usable_.points, usable_.seen_from, candidate.pose);
  work_ += kRankPointWork * usable_.points.size();
  return true;
}

void GlobalSearch::Decide() {
  const auto& o = g_.options_;
  phase_ = Phase::kDone;
  std::sort(refined_.begin(), refined_.end(),
            [](const GlobalCandidate& a, const GlobalCandidate& b) { return a.score > b.score; });
  if (refined_.empty()) {
    result_.reason = std::string(window_ ? "the search window has" : "the map has") +
                     " no place clear of walls by " + std::to_string(o.clearance_m) + " m";
    return;
  }
  // With earlier scans, how much of the newest scan alone a pose explains
  // (asked only of the best and of the poses close to it on all readings).
  auto newest_share = [&](GlobalCandidate& c) {
    if (!c.newest_score) {
      c.newest_score = g_.RankScore(newest_.points, {}, c.pose);
      work_ += kRankPointWork * newest_.points.size();
    }
    return *c.newest_score;
  };
  const double margin = o.ambiguity_margin;
  if (earlier_) newest_share(refined_.front());
  bool ambiguous = false;
  std::optional<size_t> rival;
  for (size_t i = 1; i < refined_.size() && !ambiguous; ++i) {
    if (!Distinct(refined_[i].pose, refined_.front().pose, o)) continue;
    ambiguous = refined_[i].score > refined_.front().score - margin &&
                (!earlier_ || newest_share(refined_[i]) > *refined_.front().newest_score - margin);
    if (!rival || ambiguous) rival = i;
  }
  result_.best = refined_.front();
  if (rival) result_.runner_up = refined_[*rival];
  for (const auto& r : refined_) {
    const bool distinct = std::all_of(result_.candidates.begin(), result_.candidates.end(),
                                      [&](const auto& c) { return Distinct(r.pose, c.pose, o); });
    if (distinct) result_.candidates.push_back(r);
  }
  const auto too_little = [&](double share, const char* of) {
    return "the best pose explains only " + std::to_string(static_cast<int>(100 * share)) +
           " % of " + of + " (at least " + std::to_string(static_cast<int>(100 * o.min_score)) +
           " % needed)";
  };
  if (result_.best->score < o.min_score) {
    result_.decision = GlobalDecision::kNotFound;
    result_.reason = too_little(result_.best->score, earlier_ ? "the readings" : "the scan");
  } else if (earlier_ && *result_.best->newest_score < o.min_score) {
    result_.decision = GlobalDecision::kNotFound;
    result_.reason = too_little(*result_.best->newest_score, "the newest scan alone");
  } else if (ambiguous) {
    result_.decision = GlobalDecision::kAmbiguous;
    result_.reason = earlier_
                         ? "a distinct pose explains the scan and the ones before it nearly as well"
                         : "a distinct pose explains the scan nearly as well";
  } else {
    result_.decision = GlobalDecision::kFound;
  }
}

}  // namespace structloc::localisation_core
