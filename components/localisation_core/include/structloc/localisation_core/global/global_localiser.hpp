// Global localisation: the laser poses that explain one scan against the whole
// map, for a robot with no initial pose or one that was carried away. The
// thesis' position update needs a prior pose; this search gives it one. The
// map's walls and pillar outlines are drawn into a grid and turned into a
// distance field (OpenCV's distance transform); a coarse search over positions
// and headings with a blurred field keeps the best candidates, those that are
// the best of their neighbourhood are refined by a local search on the fine
// field, and the distinct refined poses are
// polished and ranked by the share of scan points they explain (beams that
// would pass through a wall explain nothing). The best pose is "found" only
// when it explains enough points and no distinct runner-up explains nearly as
// many; two equally good poses (a symmetric corridor) give "ambiguous" rather
// than a guess. The scan may come with the ones taken just before it, placed
// by odometry (Readings, RecentScans). DDS-free, deterministic (no
// randomness).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/localisation_core/global/coarse_bounds.hpp"
#include "structloc/localisation_core/global/lattice_gains.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::localisation_core {

// The search's parameters. A separate struct with documented defaults rather
// than a section of the localisation parameter file: it is used where there is
// no pose to track yet (replay without --initial-pose, tests), and its
// defaults were tuned on the Freiburg 079 and Intel recordings and the
// simulated office, so no shipped parameter file needs to override them.
struct GlobalLocaliserOptions {
  double grid_resolution_m = 0.05;  // distance-field cell
  double grid_margin_m = 1.0;       // field border around the map's bounds
  double min_range_m = 0.1;         // readings closer are the robot itself
  double max_range_m = 30.0;        // farther readings are too noisy in angle
  int max_points = 90;              // scan points used by the refinement (evenly subsampled)
  int coarse_points = 60;           // of them, used by the coarse search
  int min_points = 20;              // fewer usable points: "not found"
  double clearance_m = 0.1;         // candidate laser positions this far from any wall
  double coarse_step_m = 0.25;      // coarse grid of positions
  double coarse_heading_step_rad = 1.5 * geometry::kPi / 180.0;  // coarse headings
  double coarse_blur_m = 0.15;  // coarse field: distances shortened by this much
  // Coarse candidates refined. With 1000, the true pose of 3 in 200 random
  // Freiburg 079 scans was never refined (long corridors fill the list with
  // near-identical hits) although it explains the scan best; 3000 finds them
  // (for 0.1-0.4 s more per scan, measured when a search took about seven
  // times as long as now).
  int coarse_keep = 3000;
  // Refinement climbs stop once their step is at most this (the last moves
  // tried are up to twice as long): the ranked poses are polished again from
  // 0.05 m, so the refinement has only to tell the places apart and order
  // them.
  double refine_precision_m = 0.02;
  double truncation_m = 0.3;          // refinement: points farther from a surface count nothing
  int ranked = 30;                    // distinct refined poses polished and ranked
  double rank_truncation_m = 0.15;    // ranking: a point farther than this explains nothing
  int rank_points = 360;              // scan points used for polishing and ranking
  double see_through_margin_m = 0.3;  // a beam crossing a wall this far before its end
                                      // explains nothing
  double min_score = 0.45;            // best pose's share of explained points for "found"
  double ambiguity_margin = 0.1;      // runner-up within this of the best: "ambiguous"
  double distinct_distance_m = 0.5;   // a runner-up is at least this far from the best ...
  double distinct_heading_rad = 10.0 * geometry::kPi / 180.0;  // ... or turned this much
};

// Whether two laser poses are distinct places for the search (at least
// distinct_distance_m apart or turned distinct_heading_rad).
bool Distinct(const geometry::Pose2D& a, const geometry::Pose2D& b,
              const GlobalLocaliserOptions& options);

enum class GlobalDecision { kFound, kAmbiguous, kNotFound };
const char* ToString(GlobalDecision decision);

struct GlobalCandidate {
  geometry::Pose2D pose;  // laser pose in the map frame
  double score = 0.0;     // share of the readings explained, 0..1
  // With earlier scans (Readings::newest_points): the share of the newest
  // scan alone explained.
  std::optional<double> newest_score;
};

// Where a local search looks: laser positions within radius_m of the centre,
// headings within heading_rad of its heading (re-acquisition after tracking
// was lost, over the odometric uncertainty).
struct SearchWindow {
  geometry::Pose2D centre;
  double radius_m = 1.0;
  double heading_rad = geometry::kPi;
};

// Readings for the search: points in the frame of the laser pose sought, the
// i-th seen from seen_from[i] in that frame. With seen_from empty every point
// was seen from the laser itself (one scan). Earlier scans, moved into this
// frame by odometry, bring the places they were taken from: each of their
// beams is then checked for passing through walls from there.
// newest_points: the first this many points are the scan being located, the
// rest earlier scans' (none: all points are that scan's). With earlier scans
// the newest must be confirmed on its own: its best pose must explain
// min_score of it too, and a distinct pose makes the answer "ambiguous" only
// if it explains nearly as much of all the readings and of the newest scan
// alone, so that neither the earlier scans (a corridor that repeats) nor the
// newest (a room like others) can hide what the other tells apart.
struct Readings {
  std::vector<Eigen::Vector2d> points;
  std::vector<Eigen::Vector2d> seen_from;
  std::optional<size_t> newest_points;
  size_t scans = 1;  // how many scans the points come from
};

// The readings of one scan, every point seen from the laser.
Readings OneScan(std::vector<Eigen::Vector2d> points);

struct GlobalResult {
  GlobalDecision decision = GlobalDecision::kNotFound;
  std::optional<GlobalCandidate> best;
  // The distinct pose that made the answer "ambiguous", else the best pose
  // distinct from `best`.
  std::optional<GlobalCandidate> runner_up;
  // Every ranked pose distinct from those before it (GlobalLocaliserOptions'
  // distinct_distance_m / distinct_heading_rad), best first: the hypotheses
  // a robot that cannot tell them apart from one scan keeps alive.
  std::vector<GlobalCandidate> candidates;
  size_t scans = 1;  // scans searched together: the newest and those before it
  size_t points_used = 0;
  // The search's work in GlobalSearch's units (see Advance), for the
  // callers that budget their searches.
  uint64_t work = 0;
  std::string reason;  // why not found or ambiguous, for the user
};

// Points of a scan in the laser frame from its ranges (beam i at angle_min +
// i * angle_increment); non-finite and out-of-range readings are left out.
std::vector<Eigen::Vector2d> ScanPointsInLaserFrame(const std::vector<float>& ranges,
                                                    double angle_min, double angle_increment,
                                                    double min_range_m, double max_range_m);

class GlobalSearch;

class GlobalLocaliser {
 public:
  // Draws the world and computes its distance field. Throws
  // std::invalid_argument naming the option when an option is out of range
  // or the grid would exceed 50 million cells.
  GlobalLocaliser(const world_model::WorldModel& world, const GlobalLocaliserOptions& options);

  // The laser poses explaining `points` (laser frame, metres), over the whole
  // map or, with `window`, only there (a pose refined to beyond the window's
  // edge by more than a coarse step is dropped).
  GlobalResult Locate(const std::vector<Eigen::Vector2d>& points,
                      const SearchWindow* window = nullptr) const;
  // The same for readings of several scans (see Readings). Throws
  // std::invalid_argument when seen_from or newest_points do not fit points.
  GlobalResult Locate(const Readings& readings, const SearchWindow* window = nullptr) const;

  // Share of `points` explained at `laser_pose` (as used for ranking).
  double Score(const std::vector<Eigen::Vector2d>& points,
               const geometry::Pose2D& laser_pose) const;
  double Score(const Readings& readings, const geometry::Pose2D& laser_pose) const;
  // Whether each point's beam passes through a wall before its end, as
  // ExplainedShare judges it; kUnknown until a share has needed it.
  enum class BeamVerdict : unsigned char { kUnknown, kClear, kBlocked };
  // Score of points already within the options' range limits (no copy), at
  // nearby poses (a tracker's prior and its correction, centimetres apart): a
  // beam's verdict is taken at the first pose that needs it and kept in
  // `verdicts` (one per point, kUnknown at first) for the others, so that
  // each beam is traced through the map once.
  double ExplainedShare(const std::vector<Eigen::Vector2d>& usable_points,
                        const geometry::Pose2D& laser_pose,
                        std::vector<BeamVerdict>& verdicts) const;

  // The points of a scan (laser frame) that a pose is fitted with and
  // weighed by: those within the options' range limits, evenly thinned to at
  // most `most`.
  std::vector<Eigen::Vector2d> FitPoints(const std::vector<Eigen::Vector2d>& points,
                                         int most) const;
  // The laser pose near `laser_pose` that explains FitPoints best: the
  // polishing climb of the ranking (moves of 5 cm and 0.01 rad, halved down
  // to 5 mm), on the sharp field.
  geometry::Pose2D Polish(const std::vector<Eigen::Vector2d>& fit_points,
                          const geometry::Pose2D& laser_pose) const;
  // How well FitPoints fit at `laser_pose`, for weighing hypotheses: the
  // share explained (as ranked) and the mean log-likelihood per point under a
  // likelihood-field model, log((1 - u) g + u) with g the ranking field's gain
  // at the point (0 when its beam passes through a wall) and u
  // `unexplained_likelihood`, the likelihood of a reading the map does not
  // explain (a person, a box).
  struct Fit {
    double share = 0.0;
    double mean_log_likelihood = 0.0;
  };
  Fit FitAt(const std::vector<Eigen::Vector2d>& fit_points, const geometry::Pose2D& laser_pose,
            double unexplained_likelihood) const;

  // How near a map point (map frame) lies to a wall or pillar outline: the
  // ranking field's gain, 1 on it, 0 at rank_truncation_m or more.
  double SurfaceGain(const Eigen::Vector2d& map_point) const {
    return Gain(rank_gain_, map_point.x(), map_point.y());
  }

  size_t CandidatePositions() const { return positions_.size(); }
  const GlobalLocaliserOptions& Options() const { return options_; }

 private:
  friend class GlobalSearch;
  struct Cells {
    int width = 0;
    int height = 0;
    double x0 = 0.0;
    double y0 = 0.0;
  };

  // Every step-th of the points (and their places seen from), at most `most`.
  static std::vector<Eigen::Vector2d> Spread(const std::vector<Eigen::Vector2d>& points, int most);
  static Readings Spread(const Readings& readings, int most);
  Readings UsableReadings(const Readings& readings) const;
  // seen_from empty: every point seen from the pose itself.
  double RankScore(const std::vector<Eigen::Vector2d>& points,
                   const std::vector<Eigen::Vector2d>& seen_from,
                   const geometry::Pose2D& pose) const;
  // A point's gain in the ranking field at `pose`, 0 when its beam from
  // `origin` (map frame) passes through a wall before it.
  double RankGain(const Eigen::Vector2d& origin, const Eigen::Vector2d& point_in_map) const;
  // Whether the beam from `origin` to `point_in_map` crosses a wall more than
  // see_through_margin_m before its end.
  bool SeenThroughWall(const Eigen::Vector2d& origin, const Eigen::Vector2d& point_in_map) const;
  bool CrossesWall(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const;
  bool InWindow(const geometry::Pose2D& pose, const SearchWindow& window) const;
  double Gain(const std::vector<float>& gain, double x, double y) const;  // bilinear, map frame
  // Hill climbing on a field, a round at a time (so that a search's slice
  // can stop between rounds): from `pose` with moves of `step` and `turn`,
  // halved whenever no move raises the score, until the step is at most
  // `precision`.
  struct Climb {
    geometry::Pose2D pose;
    double score = 0.0, step = 0.0, turn = 0.0;
    double precision = 0.0;  // done once the step falls to this
    bool Done() const { return !(step > precision); }
    // The points turned to the pose's heading, in cells (TurnPoints), and
    // to a trial heading: the moves in x and y only shift them.
    std::vector<Eigen::Vector2d> turned, trial_turned;
  };
  // `points` turned by `theta`, in cells.
  void TurnPoints(const std::vector<Eigen::Vector2d>& points, double theta,
                  std::vector<Eigen::Vector2d>& turned) const;
  // The mean gain of turned points (TurnPoints) with the laser at (x, y);
  // `work`, when given, counts the points looked up.
  double TurnedScore(const std::vector<float>& gain, const std::vector<Eigen::Vector2d>& turned,
                     double x, double y, uint64_t* work) const;
  // Bilinear gain at cell coordinates (column, row) counted from the centre
  // of cell (0, 0); 0 off the grid.
  double GainAtCell(const std::vector<float>& gain, double gx, double gy) const;
  // A climb from `pose` with first moves of `step` and `turn`, done once the
  // step falls to `precision_m`.
  Climb StartClimb(const std::vector<float>& gain, const std::vector<Eigen::Vector2d>& points,
                   const geometry::Pose2D& pose, double step, double turn, double precision_m,
                   uint64_t* work) const;
  // Polishing climbs (on the sharp field) stop at this step.
  static constexpr double kPolishPrecisionM = 0.005;
  void ClimbRound(const std::vector<float>& gain, const std::vector<Eigen::Vector2d>& points,
                  Climb& climb, uint64_t* work) const;

  // The indices of the coarse positions within `radius_m` of `centre`, in order.
  std::vector<size_t> PositionsNear(const Eigen::Vector2d& centre, double radius_m) const;

  GlobalLocaliserOptions options_;
  Cells cells_;
  // The coarse lattice: where it starts, how many rows and columns, per
  // lattice point (row major) its index in positions_, -1 where it is too
  // close to a wall, and how many positions lie before and below each
  // lattice point.
  struct Lattice {
    double x0 = 0.0, y0 = 0.0;
    int rows = 0, columns = 0;
    std::vector<int> position;
    // Positions in the lattice's rows < j and columns < i, at j * (columns + 1) + i.
    std::vector<int> positions_before;
  };
  Lattice lattice_;
  CoarseBounds coarse_bounds_;  // of coarse_gain_ over blocks of the lattice
  // The blurred field (level 0) and coarse_bounds_' grids (levels 1 to its
  // Levels()) laid out by phase: level L's blocks of 2^L x 2^L positions,
  // 2 x 2 of them at a time (a level-0 block is a position).
  std::vector<LatticeGains> phase_gains_;
  std::vector<float> fine_gain_;  // per cell: 1 - min(d, t)^2 / t^2, d to the nearest surface
  std::vector<float> rank_gain_;  // the same with the ranking truncation
  std::vector<CoarseGain> coarse_gain_;  // the same with d shortened by coarse_blur_m
  // Per cell: how far (in whole cells, centre to centre, rounded down and at
  // most 255) the nearest cell a wall or pillar outline passes through is; 0
  // in such a cell. A byte per cell, so that tracing a beam through the map
  // finds the field in the cache more often (the result is the same: the
  // trace only skips less far).
  std::vector<uint8_t> wall_distance_;
  std::vector<Eigen::Vector2d> positions_;  // coarse candidate laser positions
};

// One search of the global localiser, done a slice at a time: a tracker that
// lost the map, or a component without a pose, searches over several scans
// instead of stalling one (a search of a building takes about 0.05-0.1 s). Each
// Advance does about `work` more units (one unit: one scan point looked up in
// a distance field; a point checked for a beam through a wall counts ten),
// stopping between positions (or blocks of them), candidates or rankings;
// the result is the same however the work is sliced, and
// GlobalLocaliser::Locate is one search advanced to its end. The localiser must outlive the search.
class GlobalSearch {
 public:
  // Throws std::invalid_argument as GlobalLocaliser::Locate does.
  GlobalSearch(const GlobalLocaliser& localiser, const Readings& readings,
               std::optional<SearchWindow> window = std::nullopt);
  // Does about `work` units more (at least one step); true when done.
  bool Advance(uint64_t work);
  bool Done() const { return phase_ == Phase::kDone; }
  const GlobalResult& Result() const { return result_; }  // once done
  uint64_t WorkDone() const { return work_; }
  // The work a whole search of one scan over `positions` lattice positions
  // takes at most before its refinement (to size the slices).
  static uint64_t CoarseWork(const GlobalLocaliserOptions& options, size_t positions);

 private:
  enum class Phase { kCoarse, kRefine, kRank, kDone };
  // The coarse phase (global_coarse_search.cpp): one step scores a position
  // of the window, or (over the whole map) bounds one top-level block or
  // expands one block of the branch and bound into its four quarters.
  void CoarseStep();
  // The coarse scores of position k at `headings` (in increasing order), and its
  // hits: the best heading and the best one clearly turned from it.
  void CoarsePosition(size_t k, const std::vector<uint16_t>& headings);
  // Position k's hits from its scores at `headings` (in increasing order).
  void AddHits(size_t k, const std::vector<uint16_t>& headings, const std::vector<float>& scores);
  // The score below which a hit can no longer be among the coarse_keep best.
  float KeepThreshold() const;
  struct BoundedHeading {
    uint16_t heading;
    float bound;
  };
  struct Block {
    int level = 0, column = 0, row = 0;  // its first lattice position
    size_t first = 0, end = 0;  // its headings in top_headings_ (top level) or block_headings_
    float bound = 0.0f;         // the best of its headings' bounds
  };
  bool BlockHasPositions(const Block& block) const;
  // The coarse scores of a level-1 block's positions at the headings being
  // expanded, and their hits.
  void CoarseBlock(const Block& block);
  // The block's headings (of `headings`) whose bound reaches KeepThreshold,
  // into `out`; the block's bound is the best of them.
  void BoundBlock(Block& block, const std::vector<uint16_t>& headings,
                  const std::vector<float>& bounds, std::vector<BoundedHeading>& out);
  // The sums at `level` (phase_gains_: 0 the positions' scores, above the
  // blocks' bounds) of the 2 x 2 level-`level` blocks from (column, row),
  // counted in such blocks, at `headings`: out[q][h] for block
  // (column + q % 2, row + q / 2).
  void SumFour(int level, int column, int row, const std::vector<uint16_t>& headings,
               const std::array<std::vector<float>*, 4>& out) const;
  void ExpandBlock(const Block& block);
  void SelectHits();
  // Of the kept hits, keeps only those no neighbour outscores (see
  // global_search.cpp).
  void KeepLocalMaxima();
  // One round of the climb of hit (candidate) `i`; true when its climb is done.
  bool RefineHit(size_t i);
  void ChooseRanked();
  bool RankCandidate(size_t i);
  void Decide();

  const GlobalLocaliser& g_;
  std::optional<SearchWindow> window_;
  GlobalResult result_;
  Phase phase_ = Phase::kCoarse;
  uint64_t work_ = 0;
  size_t next_ = 0;  // position, hit or candidate next in its phase
  Readings usable_;
  std::vector<Eigen::Vector2d> points_;  // spread for the refinement
  bool earlier_ = false;
  Readings newest_;
  int headings_ = 1;
  double heading_step_ = 0.0;
  int separation_ = 1;
  size_t coarse_count_ = 0;
  // Per heading, per coarse point: its cell's column and row from the
  // position's (the lattice's positions lie on cell corners).
  std::vector<int> offsets_;
  // The same prepared for phase_gains_: per level, per heading, per coarse point.
  std::vector<std::vector<LatticeGains::Offset>> phase_offsets_;
  std::vector<float> quarter_bounds_[4];  // a block's quarters', per heading
  // The top-level blocks' bounds, per heading, of two rows of them (their
  // row modulo 2, then column), computed 2 x 2 blocks at a time.
  std::vector<std::vector<float>> top_bounds_;
  // A lattice position's cell.
  int CellColumn(double x) const;
  int CellRow(double y) const;
  // With a window, the coarse positions in it (else every position is tried).
  std::vector<size_t> window_positions_;
  std::vector<float> scores_;
  std::vector<float> block_scores_[4];  // CoarseBlock's, per position of the block
  // The headings positions are scored at: all of them, or a window's.
  std::vector<uint16_t> scored_headings_;
  // The branch and bound over the whole map: the top-level blocks not yet
  // bounded (next_top_ on), the blocks waiting to be expanded (a stack, the
  // most promising on top), their headings (and those of the block being
  // expanded, and of its quarters), and the coarse_keep best hit scores so
  // far (a min-heap).
  size_t next_top_ = 0;
  std::vector<Block> tops_, blocks_;
  std::vector<BoundedHeading> top_headings_, block_headings_;
  std::vector<uint16_t> expanding_;
  std::vector<BoundedHeading> quarter_headings_[4];
  std::vector<float> kept_scores_;
  struct CoarseHit {
    float score;
    int position;
    int heading;
  };
  std::vector<CoarseHit> hits_;
  size_t keep_ = 0;
  std::vector<char> dropped_;  // per kept hit: a neighbour outscores it
  std::vector<GlobalCandidate> converged_;
  std::vector<GlobalCandidate> refined_;
  std::optional<GlobalLocaliser::Climb> climb_;  // of the hit or candidate next_
};

}  // namespace structloc::localisation_core
