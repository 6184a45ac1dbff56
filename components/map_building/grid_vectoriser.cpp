// Walls, corners and pillars from an occupancy grid (see header).
#include "structloc/map_building/grid_vectoriser.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <climits>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "structloc/map_building/option_check.hpp"

namespace structloc::map_building {
namespace {

using map_building::OccupancyGrid;

// Bad options are refused as "grid import option ...".
constexpr const char* kOptions = "grid import";

void CheckOptions(const GridVectoriseOptions& o) {
  RequireOption(o.free_max_value >= 0 && o.free_max_value < o.occupied_min_value &&
                    o.occupied_min_value <= 100,
                kOptions,
                "free_max_value and occupied_min_value must satisfy 0 <= free < occupied <= 100");
  RequireOption(o.min_wall_length_m > 0.0, kOptions, "min_wall_length_m must be positive");
  RequireOption(o.max_gap_m > 0.0, kOptions, "max_gap_m must be positive");
  RequireOption(o.min_wall_blob_size_m >= 0.0, kOptions,
                "min_wall_blob_size_m must not be negative");
  RequireOption(o.max_join_gap_m >= 0.0 && o.max_join_gap_m <= 1.0, kOptions,
                "max_join_gap_m must lie in [0, 1] m");
  RequireOption(o.proposal_capture_cells > 0.0 && o.capture_cells > 0.0, kOptions,
                "proposal_capture_cells and capture_cells must be positive");
  RequireOption(o.same_line_angle_rad > 0.0, kOptions, "same_line_angle_rad must be positive");
  RequireOption(o.hough_votes >= 2, kOptions, "hough_votes must be at least 2");
  RequireOption(o.min_pillar_radius_m > 0.0 && o.min_pillar_radius_m <= o.max_pillar_radius_m,
                kOptions, "min_pillar_radius_m must be positive and at most max_pillar_radius_m");
  RequireOption(o.max_pillar_rms_cells > 0.0, kOptions, "max_pillar_rms_cells must be positive");
  RequireOption(o.min_pillar_roundness > 0.0 && o.min_pillar_roundness <= 1.0, kOptions,
                "min_pillar_roundness must lie in (0, 1]");
  RequireOption(o.max_face_cells > 0 && o.max_blobs > 0 && o.max_refit_work > 0, kOptions,
                "max_face_cells, max_blobs and max_refit_work must be positive");
}

// The refusal of a grid that needs more work than `option` allows.
[[noreturn]] void OverBudget(const std::string& what, const std::string& option, size_t limit) {
  std::string flag = "--" + option;
  std::replace(flag.begin(), flag.end(), '_', '-');
  throw std::invalid_argument(what + ", more than the option " + option + " allows (" +
                              std::to_string(limit) + "; " + flag +
                              " of structloc map import): is it noise rather than a map? A "
                              "larger map may need a larger limit");
}

// Counts the refits' work against max_refit_work.
class RefitBudget {
 public:
  explicit RefitBudget(size_t limit) : limit_(limit) {}
  void Spend(size_t gathered, size_t walked) {
    walked_ += walked;
    work_ += gathered + walked_ / 16;
    walked_ %= 16;
    if (work_ > limit_) {
      OverBudget("refitting the wall proposals takes more than " + std::to_string(limit_) +
                     " cells of work",
                 "max_refit_work", limit_);
    }
  }

 private:
  size_t limit_;
  size_t work_ = 0;
  size_t walked_ = 0;
};

// A cell this near a fitted line counts as lying on it (a wall two cells
// thick has its cells half a cell either side of its line).
constexpr double kOnLineCells = 0.55;

struct Line {
  Eigen::Vector2d normal{1, 0};
  double r = 0.0;
  double Distance(const Eigen::Vector2d& p) const { return std::abs(normal.dot(p) - r); }
  Eigen::Vector2d Direction() const { return {-normal.y(), normal.x()}; }
};

Line LineOf(const FittedWall& wall) {
  return {Eigen::Vector2d(std::cos(wall.line.alpha), std::sin(wall.line.alpha)), wall.line.r};
}

// Cell-centre points of one line, split into runs at gaps, runs shorter than
// min_length dropped.
std::vector<std::vector<Eigen::Vector2d>> Runs(const std::vector<Eigen::Vector2d>& points,
                                               double max_gap, double min_length) {
  std::vector<std::vector<Eigen::Vector2d>> kept;
  if (points.size() < 3) return kept;
  const FittedWall all = FitWall(points);
  for (auto& run : SplitAtGaps(all, points, max_gap)) {
    if (run.size() < 3) continue;
    const double length = std::abs(AlongWall(all, run.back()) - AlongWall(all, run.front()));
    if (length >= min_length) kept.push_back(std::move(run));
  }
  return kept;
}

std::vector<Eigen::Vector2d> Joined(const std::vector<std::vector<Eigen::Vector2d>>& runs) {
  std::vector<Eigen::Vector2d> all;
  for (const auto& run : runs) all.insert(all.end(), run.begin(), run.end());
  return all;
}

// The face cells, found by cell: lines are walked across the grid instead of
// testing every face cell against every line. The cells are marked in an
// image (255) that Hough's proposals are drawn from; a cell's point is its
// centre. Blocks of kBlock x kBlock cells without a face cell are stepped over
// (a grid the face-cell limit lets through leaves most of them empty).
class FaceCells {
 public:
  explicit FaceCells(const OccupancyGrid& grid)
      : grid_(grid),
        centre_(grid),
        image_(grid.height, grid.width, CV_8UC1, cv::Scalar(0)),
        blocks_((grid.height + kBlock - 1) / kBlock, (grid.width + kBlock - 1) / kBlock, CV_8UC1,
                cv::Scalar(0)) {}
  void Add(int column, int row) {
    image_.at<uint8_t>(row, column) = 255;
    blocks_.at<uint8_t>(row / kBlock, column / kBlock) = 1;
    ++count_;
  }
  size_t Count() const { return count_; }
  const cv::Mat& Image() const { return image_; }
  long long KeyOf(const Eigen::Vector2d& p) const {
    const Eigen::Vector2i cell = grid_.CellOf(p);
    return static_cast<long long>(grid_.Index(cell.x(), cell.y()));
  }
  // Face cells whose centre is at most `distance` from the line, its work
  // spent from `budget`.
  std::vector<Eigen::Vector2d> Near(const Line& line, double distance, RefitBudget& budget) const {
    // The line in cell units: n_g . u = r_g, u = (column + 0.5, row + 0.5) at centres.
    const double c = std::cos(grid_.origin.z()), s = std::sin(grid_.origin.z());
    const Eigen::Vector2d n(c * line.normal.x() + s * line.normal.y(),
                            -s * line.normal.x() + c * line.normal.y());
    const double r = (line.r - line.normal.dot(grid_.origin.head<2>())) / grid_.resolution_m;
    const double d = distance / grid_.resolution_m;
    const bool by_column = std::abs(n.y()) >= std::abs(n.x());
    const int steps = by_column ? grid_.width : grid_.height;
    const int across_size = by_column ? grid_.height : grid_.width;
    const double major = by_column ? n.x() : n.y(), minor = by_column ? n.y() : n.x();
    const double spread = d / std::abs(minor) + 1.0;
    // The cells across step i that may lie within `distance` (not clipped to the grid).
    const auto across = [&](int i) {
      const double centre = (r - major * (i + 0.5)) / minor - 0.5;
      return std::pair<int, int>(static_cast<int>(std::floor(centre - spread)),
                                 static_cast<int>(std::ceil(centre + spread)));
    };
    std::vector<Eigen::Vector2d> near;
    for (int first = 0; first < steps; first += kBlock) {
      // The band of a block's steps, stepped over when its blocks hold no face cell.
      const int last = std::min(steps, first + kBlock) - 1;
      const auto [first_lo, first_hi] = across(first);
      const auto [last_lo, last_hi] = across(last);
      if (!AnyInBlocks(by_column, first, std::max(0, std::min(first_lo, last_lo)),
                       std::min(across_size - 1, std::max(first_hi, last_hi))))
        continue;
      for (int i = first; i <= last; ++i) {
        const auto [unclipped_lo, unclipped_hi] = across(i);
        const int lo = std::max(0, unclipped_lo), hi = std::min(across_size - 1, unclipped_hi);
        for (int j = lo; j <= hi; ++j) {
          const int column = by_column ? i : j, row = by_column ? j : i;
          if (image_.at<uint8_t>(row, column) == 0) continue;
          const Eigen::Vector2d point = centre_(column, row);
          if (line.Distance(point) <= distance) near.push_back(point);
        }
      }
    }
    budget.Spend(near.size(), static_cast<size_t>(steps));
    return near;
  }

 private:
  static constexpr int kBlock = 16;
  // Whether a face cell may lie in the blocks of column (by_column) or row
  // `i`, from `lo` to `hi` across (none when lo > hi).
  bool AnyInBlocks(bool by_column, int i, int lo, int hi) const {
    if (lo > hi) return false;
    for (int block = lo / kBlock; block <= hi / kBlock; ++block) {
      if (by_column ? blocks_.at<uint8_t>(block, i / kBlock)
                    : blocks_.at<uint8_t>(i / kBlock, block))
        return true;
    }
    return false;
  }
  const OccupancyGrid& grid_;
  CellCentres centre_;
  cv::Mat image_;
  cv::Mat blocks_;  // per block of cells, 1 when it holds a face cell
  size_t count_ = 0;
};

// A circle through a blob's boundary cells, refitted once without the cells
// more than a cell off the first fit (noise cells stuck to the pillar); the
// first fit when more than a fifth of them would be dropped; nothing when the
// cells lie on a line (a short diagonal stroke is no pillar).
std::optional<FittedCircle> FitPillar(const std::vector<Eigen::Vector2d>& edge, double cell) {
  try {
    const FittedCircle first = FitCircle(edge);
    std::vector<Eigen::Vector2d> inliers;
    for (const auto& p : edge)
      if (std::abs((p - first.centre).norm() - first.radius) <= cell) inliers.push_back(p);
    if (inliers.size() < 6 || inliers.size() * 5 < edge.size() * 4) return first;
    return FitCircle(inliers);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

struct Blob {
  int left, bottom, width, height;
  size_t cells;
};

// The join's dilation costs time in proportion to the gap in cells: a grid
// whose cells are far finer than max_join_gap_m (a millimetre grid of a
// small area, or a malformed YAML's resolution) joins at most this many.
constexpr double kMaxJoinGapCells = 64;

// What a blob is judged by: the extent (long side, cells) and the cell count
// of its group, the blobs whose cells lie at most gap_cells empty cells apart.
// A wall seen by few scans comes out of a ray-cast grid dotted, in blobs of a
// few cells each, none of them as long as the wall; joined, they are.
struct BlobGroup {
  int long_side = 0;
  size_t cells = 0;
};
std::vector<BlobGroup> GroupsOfBlobs(const cv::Mat& mask, const cv::Mat& labels,
                                     const std::vector<Blob>& blobs, int gap_cells) {
  const int count = static_cast<int>(blobs.size());
  std::vector<BlobGroup> of_blob(blobs.size());
  if (gap_cells == 0) {  // each blob alone
    for (size_t i = 1; i < blobs.size(); ++i)
      of_blob[i] = {std::max(blobs[i].width, blobs[i].height), blobs[i].cells};
    return of_blob;
  }
  // A (gap + 1)-square kernel anchored at its corner stretches each cell by
  // gap cells towards the first column and row: cells up to gap empty cells
  // apart, along either axis or diagonally (in cells), then touch.
  cv::Mat joined, group_labels;
  cv::dilate(mask, joined, cv::Mat::ones(gap_cells + 1, gap_cells + 1, CV_8UC1), {0, 0});
  const int groups = cv::connectedComponents(joined, group_labels, 8, CV_32S);
  struct Extent {
    int left = INT_MAX, right = INT_MIN, bottom = INT_MAX, top = INT_MIN;
    size_t cells = 0;
  };
  std::vector<Extent> extents(static_cast<size_t>(groups));
  std::vector<int> group_of(static_cast<size_t>(count), 0);
  for (int r = 0; r < labels.rows; ++r) {
    const uint8_t* occupied = mask.ptr<uint8_t>(r);
    for (int c = 0; c < labels.cols; ++c) {
      if (occupied[c] == 0) continue;  // background, label 0
      const int label = labels.at<int>(r, c);
      const int g = group_labels.at<int>(r, c);
      group_of[static_cast<size_t>(label)] = g;
      auto& e = extents[static_cast<size_t>(g)];
      e.left = std::min(e.left, c);
      e.right = std::max(e.right, c);
      e.bottom = std::min(e.bottom, r);
      e.top = std::max(e.top, r);
      ++e.cells;
    }
  }
  for (int i = 1; i < count; ++i) {
    const auto& e = extents[static_cast<size_t>(group_of[static_cast<size_t>(i)])];
    of_blob[static_cast<size_t>(i)] = {std::max(e.right - e.left, e.top - e.bottom) + 1, e.cells};
  }
  return of_blob;
}

}  // namespace

FittedCircle FitCircle(const std::vector<Eigen::Vector2d>& points) {
  if (points.size() < 3) throw std::invalid_argument("a circle needs at least three points");
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  // Kasa: x^2 + y^2 + D x + E y + F = 0, about the mean for conditioning.
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector2d q = p - mean;
    const Eigen::Vector3d row(q.x(), q.y(), 1.0);
    ata += row * row.transpose();
    atb += row * -q.squaredNorm();
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(ata);
  if (lu.rank() < 3) throw std::invalid_argument("circle points are collinear");
  const Eigen::Vector3d def = lu.solve(atb);
  Eigen::Vector2d centre(-def[0] / 2.0, -def[1] / 2.0);
  double radius = std::sqrt(std::max(0.0, centre.squaredNorm() - def[2]));
  // Geometric refinement (Gauss-Newton on |p - c| - R).
  for (int iteration = 0; iteration < 20; ++iteration) {
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jtr = Eigen::Vector3d::Zero();
    for (const auto& p : points) {
      const Eigen::Vector2d d = (p - mean) - centre;
      const double n = d.norm();
      if (n < 1e-12) continue;
      const Eigen::Vector3d j(-d.x() / n, -d.y() / n, -1.0);
      jtj += j * j.transpose();
      jtr += j * (n - radius);
    }
    const Eigen::Vector3d step = jtj.ldlt().solve(-jtr);
    if (!step.allFinite()) break;
    centre += step.head<2>();
    radius += step[2];
    if (step.norm() < 1e-10) break;
  }
  double sse = 0.0;
  for (const auto& p : points) sse += std::pow(((p - mean) - centre).norm() - radius, 2);
  FittedCircle circle;
  circle.centre = centre + mean;
  circle.radius = std::abs(radius);
  circle.rms_m = std::sqrt(sse / static_cast<double>(points.size()));
  return circle;
}

namespace {

// Which cells of the grid are occupied, free, open and faces, by the
// options' thresholds.
class CellKinds {
 public:
  CellKinds(const OccupancyGrid& grid, const GridVectoriseOptions& options)
      : grid_(grid), options_(options) {
    for (int r = 0; r < grid.height && !any_free_; ++r) {
      for (int c = 0; c < grid.width && !any_free_; ++c) any_free_ = !Occupied(c, r) && Free(c, r);
    }
  }
  bool Occupied(int c, int r) const {
    return grid_.Contains(c, r) && grid_.At(c, r) >= options_.occupied_min_value;
  }
  bool Free(int c, int r) const {
    return grid_.Contains(c, r) && grid_.At(c, r) >= 0 && grid_.At(c, r) <= options_.free_max_value;
  }
  // A face looks onto free space; a grid without free cells (only occupied
  // and unknown) has its faces looking onto anything not occupied.
  bool Open(int c, int r) const { return any_free_ ? Free(c, r) : !Occupied(c, r); }
  bool Face(int c, int r) const {
    return Open(c - 1, r) || Open(c + 1, r) || Open(c, r - 1) || Open(c, r + 1);
  }

 private:
  const OccupancyGrid& grid_;
  const GridVectoriseOptions& options_;
  bool any_free_ = false;
};

// The occupied cells (255), refused when there are none or when Hough would
// have more face cells to vote with than max_face_cells.
cv::Mat OccupiedMask(const OccupancyGrid& grid, const CellKinds& kinds,
                     const GridVectoriseOptions& options, size_t& occupied) {
  cv::Mat mask(grid.height, grid.width, CV_8UC1, cv::Scalar(0));
  for (int r = 0; r < grid.height; ++r) {
    const int8_t* cells = grid.cells.data() + grid.Index(0, r);
    uint8_t* out = mask.ptr<uint8_t>(r);
    for (int c = 0; c < grid.width; ++c) {
      if (cells[c] < options.occupied_min_value) continue;
      out[c] = 255;
      ++occupied;
    }
  }
  if (occupied == 0)
    throw std::invalid_argument("the grid has no occupied cell (none at or above " +
                                std::to_string(options.occupied_min_value) +
                                "): nothing to import");
  // Hough's time grows with the face cells: bounded before any blob is made.
  size_t all_faces = 0;
  for (int r = 0; r < grid.height; ++r) {
    const uint8_t* in = mask.ptr<uint8_t>(r);
    for (int c = 0; c < grid.width; ++c) all_faces += in[c] != 0 && kinds.Face(c, r);
  }
  if (all_faces > options.max_face_cells) {
    OverBudget("the grid has " + std::to_string(all_faces) + " occupied cells next to open space",
               "max_face_cells", options.max_face_cells);
  }
  return mask;
}

// The 8-connected blobs of occupied cells (index 0: the background).
struct Blobs {
  cv::Mat labels;  // per cell, its blob
  std::vector<Blob> blobs;
  int Count() const { return static_cast<int>(blobs.size()); }
};

Blobs FindBlobs(const cv::Mat& mask, const GridVectoriseOptions& options) {
  Blobs out;
  cv::Mat stats, centroids;
  const int count = cv::connectedComponentsWithStats(mask, out.labels, stats, centroids, 8, CV_32S);
  if (static_cast<size_t>(count - 1) > options.max_blobs) {
    OverBudget("the grid has " + std::to_string(count - 1) + " blobs of occupied cells",
               "max_blobs", options.max_blobs);
  }
  out.blobs.resize(static_cast<size_t>(count));
  for (int i = 1; i < count; ++i) {
    out.blobs[static_cast<size_t>(i)] = {
        stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
        stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT),
        static_cast<size_t>(stats.at<int>(i, cv::CC_STAT_AREA))};
  }
  return out;
}

// Boundary cells of the blobs shaped like a pillar (small and round), the
// only ones a circle is fitted to: per blob its slot in `cells` (-1: none).
struct PillarBoundaries {
  std::vector<int> slot;
  std::vector<std::vector<Eigen::Vector2d>> cells;
};

PillarBoundaries PillarShapedBoundaries(const OccupancyGrid& grid, const CellKinds& kinds,
                                        const Blobs& found, const GridVectoriseOptions& options) {
  const double res = grid.resolution_m;
  const auto pillar_shaped = [&](const Blob& blob) {
    const double long_side = std::max(blob.width, blob.height) * res;
    const double short_side = std::min(blob.width, blob.height) * res;
    return long_side <= 2.0 * options.max_pillar_radius_m + 2.0 * res &&
           short_side >= options.min_pillar_roundness * long_side;
  };
  PillarBoundaries out;
  out.slot.assign(found.blobs.size(), -1);
  for (int i = 1; i < found.Count(); ++i) {
    if (!pillar_shaped(found.blobs[static_cast<size_t>(i)])) continue;
    out.slot[static_cast<size_t>(i)] = static_cast<int>(out.cells.size());
    out.cells.emplace_back();
  }
  for (int i = 1; i < found.Count(); ++i) {
    const int slot = out.slot[static_cast<size_t>(i)];
    if (slot < 0) continue;
    const Blob& blob = found.blobs[static_cast<size_t>(i)];
    for (int r = blob.bottom; r < blob.bottom + blob.height; ++r) {
      for (int c = blob.left; c < blob.left + blob.width; ++c) {
        if (found.labels.at<int>(r, c) != i) continue;
        if (!kinds.Occupied(c - 1, r) || !kinds.Occupied(c + 1, r) || !kinds.Occupied(c, r - 1) ||
            !kinds.Occupied(c, r + 1))
          out.cells[static_cast<size_t>(slot)].push_back(grid.CellCentre(c, r));
      }
    }
  }
  return out;
}

// Classifies the blobs (judged with those up to max_join_gap_m away):
// specks and the rest left out, pillars into out.pillars, and walls, whose
// blobs it returns (true per blob label).
std::vector<bool> ClassifyBlobs(const OccupancyGrid& grid, const cv::Mat& mask, const Blobs& found,
                                const PillarBoundaries& boundaries,
                                const GridVectoriseOptions& options, GridVectorisation& out) {
  const double res = grid.resolution_m;
  // Whole cells of gap, at most kMaxJoinGapCells.
  const double gap_cells =
      std::min(std::floor(options.max_join_gap_m / res + 1e-9), kMaxJoinGapCells);
  const auto groups = GroupsOfBlobs(mask, found.labels, found.blobs, static_cast<int>(gap_cells));
  std::vector<bool> is_wall(found.blobs.size(), false);
  for (int i = 1; i < found.Count(); ++i) {
    const BlobGroup& group = groups[static_cast<size_t>(i)];
    if (group.cells <= options.max_speck_cells) {
      ++out.specks_left_out;
      continue;
    }
    const int slot = boundaries.slot[static_cast<size_t>(i)];
    if (slot >= 0 && boundaries.cells[static_cast<size_t>(slot)].size() >= 6) {
      const auto circle = FitPillar(boundaries.cells[static_cast<size_t>(slot)], res);
      if (circle && circle->radius >= options.min_pillar_radius_m &&
          circle->radius <= options.max_pillar_radius_m &&
          circle->rms_m <= options.max_pillar_rms_cells * res) {
        out.pillars.push_back({0, circle->centre, circle->radius});
        continue;
      }
    }
    if (group.long_side * res >= options.min_wall_blob_size_m) {
      is_wall[static_cast<size_t>(i)] = true;
      ++out.wall_blobs;
    } else {
      ++out.blobs_left_out;
    }
  }
  return is_wall;
}

// One proposal refitted on its own (see WallCandidates).
struct Candidate {
  FittedWall fit;
  std::vector<std::vector<Eigen::Vector2d>> runs;
  std::vector<long long> cells;  // keys of the cells fitted, each once
  size_t on_line = 0;            // cells within kOnLineCells of the line
  bool dropped = false;
};

// A Hough segment (cell coordinates) refitted on the face cells: first on
// those along it, then on its whole line until its cells settle; nullopt when
// no run of cells long enough is left.
std::optional<Candidate> Refit(const cv::Vec4i& s, const OccupancyGrid& grid,
                               const FaceCells& face_cells, const GridVectoriseOptions& options,
                               RefitBudget& budget) {
  const double res = grid.resolution_m;
  const Eigen::Vector2d a = grid.CellCentre(s[0], s[1]), b = grid.CellCentre(s[2], s[3]);
  if ((b - a).norm() < 1e-9) return std::nullopt;
  Line proposed;
  proposed.normal = Eigen::Vector2d(-(b - a).y(), (b - a).x()).normalized();
  proposed.r = proposed.normal.dot(a);
  const Eigen::Vector2d mid = (a + b) / 2.0;
  // Start: the cells along the proposed segment (and a gap beyond its ends).
  const Eigen::Vector2d direction = proposed.Direction();
  const double half = (b - a).norm() / 2.0 + options.max_gap_m;
  std::vector<Eigen::Vector2d> start;
  for (const auto& p : face_cells.Near(proposed, options.proposal_capture_cells * res, budget))
    if (std::abs(direction.dot(p - mid)) <= half) start.push_back(p);
  auto runs = Runs(start, options.max_gap_m, options.min_wall_length_m);
  if (runs.empty()) return std::nullopt;
  // Then the whole line, refitted until its cells settle (first with the
  // wider capture, so that a slightly turned start swings back): every piece
  // of the line (across doors) is fitted jointly.
  FittedWall fit = FitWall(Joined(runs));
  for (int iteration = 0; iteration < 4 && !runs.empty(); ++iteration) {
    const double capture =
        (iteration < 2 ? options.proposal_capture_cells : options.capture_cells) * res;
    runs = Runs(face_cells.Near(LineOf(fit), capture, budget), options.max_gap_m,
                options.min_wall_length_m);
    if (!runs.empty()) fit = FitWall(Joined(runs));
  }
  if (runs.empty()) return std::nullopt;
  Candidate candidate{fit, runs, {}, 0, false};
  const Line fitted = LineOf(fit);
  for (const auto& run : runs) {
    for (const auto& p : run) {
      candidate.cells.push_back(face_cells.KeyOf(p));
      candidate.on_line += fitted.Distance(p) <= kOnLineCells * res;
    }
  }
  // Each cell once (a cell centre far from the origin may round into its
  // neighbour's cell).
  std::sort(candidate.cells.begin(), candidate.cells.end());
  candidate.cells.erase(std::unique(candidate.cells.begin(), candidate.cells.end()),
                        candidate.cells.end());
  return candidate;
}

// The walls' Hough proposals, longest first, each refitted on its own;
// proposals that end on the same cells (near-parallel, sharing half of them)
// are one wall, and the fit with the most cells within ~half a cell of its
// line wins (not simply the most cells: a line slanting across a thick
// wall's two faces collects as many cells as either face, but few of them
// lie on it). Those that lost are marked dropped.
std::vector<Candidate> WallCandidates(const OccupancyGrid& grid, const FaceCells& face_cells,
                                      const GridVectoriseOptions& options) {
  const double res = grid.resolution_m;
  std::vector<cv::Vec4i> proposals;
  if (face_cells.Count() > 0) {
    cv::HoughLinesP(face_cells.Image(), proposals, 1.0, CV_PI / 720.0, options.hough_votes,
                    options.min_wall_length_m / res, options.max_gap_m / res);
  }
  auto length = [](const cv::Vec4i& s) { return std::hypot(s[2] - s[0], s[3] - s[1]); };
  std::stable_sort(proposals.begin(), proposals.end(),
                   [&](const auto& l, const auto& m) { return length(l) > length(m); });
  std::vector<Candidate> candidates;
  RefitBudget budget(options.max_refit_work);
  std::unordered_map<long long, std::vector<size_t>> candidates_of_cell;
  std::vector<size_t> sharers;  // per cell shared, the earlier candidate sharing it
  for (const auto& s : proposals) {
    auto refit = Refit(s, grid, face_cells, options, budget);
    if (!refit) continue;
    Candidate& candidate = *refit;
    const Line fitted = LineOf(candidate.fit);
    // The earlier candidates that share cells with this one, in the order
    // they came, with how many cells each shares (found by cell: comparing
    // with every earlier candidate made a noisy grid's import quadratic).
    sharers.clear();
    for (const long long key : candidate.cells) {
      const auto found = candidates_of_cell.find(key);
      if (found != candidates_of_cell.end())
        sharers.insert(sharers.end(), found->second.begin(), found->second.end());
    }
    std::sort(sharers.begin(), sharers.end());
    for (size_t first = 0, last = 0; first < sharers.size(); first = last) {
      const size_t index = sharers[first];
      while (last < sharers.size() && sharers[last] == index) ++last;
      const size_t shared = last - first;
      auto& other = candidates[index];
      if (other.dropped) continue;
      const Line known = LineOf(other.fit);
      const double cross =
          known.normal.x() * fitted.normal.y() - known.normal.y() * fitted.normal.x();
      if (std::abs(cross) > std::sin(options.same_line_angle_rad)) continue;
      if (2 * shared < std::min(candidate.cells.size(), other.cells.size())) continue;
      if (other.on_line >= candidate.on_line) {
        candidate.dropped = true;
        break;
      }
      other.dropped = true;
    }
    if (candidate.dropped) continue;
    for (const long long key : candidate.cells)
      candidates_of_cell[key].push_back(candidates.size());
    candidates.push_back(std::move(candidate));
  }
  return candidates;
}

// Each run of a wall that won is one wall piece, from its first cell to its
// last along the fitted line.
void AppendWallPieces(const std::vector<Candidate>& candidates, std::vector<FittedWall>& walls) {
  for (const auto& candidate : candidates) {
    if (candidate.dropped) continue;
    const Line fitted = LineOf(candidate.fit);
    const Eigen::Vector2d foot = fitted.r * fitted.normal;
    for (const auto& run : candidate.runs) {
      FittedWall piece = candidate.fit;
      double lo = INFINITY, hi = -INFINITY;
      for (const auto& p : run) {
        const double t = fitted.Direction().dot(p - foot);
        lo = std::min(lo, t);
        hi = std::max(hi, t);
      }
      piece.a = foot + lo * fitted.Direction();
      piece.b = foot + hi * fitted.Direction();
      piece.points = run.size();
      walls.push_back(piece);
    }
  }
}

}  // namespace

GridVectorisation VectoriseGrid(const OccupancyGrid& grid, const GridVectoriseOptions& options) {
  CheckOptions(options);
  if (grid.width < 0 || grid.height < 0 ||
      grid.cells.size() != static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height))
    throw std::invalid_argument("the grid's cells (" + std::to_string(grid.cells.size()) +
                                ") do not match its " + std::to_string(grid.width) + " x " +
                                std::to_string(grid.height) + " cells");
  GridVectorisation out;
  out.cells = grid.cells.size();
  const CellKinds kinds(grid, options);
  const cv::Mat mask = OccupiedMask(grid, kinds, options, out.occupied_cells);
  const Blobs found = FindBlobs(mask, options);
  const PillarBoundaries boundaries = PillarShapedBoundaries(grid, kinds, found, options);
  const std::vector<bool> is_wall = ClassifyBlobs(grid, mask, found, boundaries, options, out);

  // Face cells of the wall blobs: the points the walls are fitted to.
  FaceCells face_cells(grid);
  for (int r = 0; r < grid.height; ++r) {
    const uint8_t* occupied = mask.ptr<uint8_t>(r);
    for (int c = 0; c < grid.width; ++c) {
      if (occupied[c] != 0 && is_wall[static_cast<size_t>(found.labels.at<int>(r, c))] &&
          kinds.Face(c, r))
        face_cells.Add(c, r);
    }
  }
  out.face_cells = face_cells.Count();
  AppendWallPieces(WallCandidates(grid, face_cells, options), out.walls);
  // Refused before the corners are joined (the slowest step on such grids):
  // no world could hold these walls.
  if (out.walls.size() > world_model::WorldLimits::kDefaultMaxWalls)
    throw std::invalid_argument("the grid gives " + std::to_string(out.walls.size()) +
                                " walls, more than the limit of " +
                                std::to_string(world_model::WorldLimits::kDefaultMaxWalls) +
                                " walls per map: is it noise rather than a map?");
  CornerJoinOptions corners = options.corners;
  corners.max_end_distance_m = std::max(corners.max_end_distance_m, 3.0 * grid.resolution_m);
  out.corners_joined = JoinCorners(out.walls, corners);
  out.short_after_joining = DropShortWalls(out.walls, options.min_wall_length_m);
  return out;
}

}  // namespace structloc::map_building
