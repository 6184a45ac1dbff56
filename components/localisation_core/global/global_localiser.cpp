// Global localisation against the whole map (see header): its options, the
// distance fields and the scores of a pose; the search itself is in
// global_search.cpp.
#include "structloc/localisation_core/global/global_localiser.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

#include "structloc/localisation_core/global/wall_crossing.hpp"
#include "structloc/world_model/outline_points.hpp"

namespace structloc::localisation_core {
namespace {

constexpr double kMaxCells = 50e6;
// Blocks of up to 4 x 4 lattice positions (1 m at the default step) are
// bounded: the bound of larger blocks on the blurred field is too loose to
// prune much, and costs as much to take as the positions' scores (measured
// on the Intel recording with 1, 2 and 4 levels).
constexpr int kCoarseBoundLevels = 2;

void RequirePositive(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::invalid_argument(std::string("global localiser option ") + name +
                                " must be a positive number");
}

void Check(const GlobalLocaliserOptions& o) {
  RequirePositive(o.grid_resolution_m, "grid_resolution_m");
  RequirePositive(o.max_range_m, "max_range_m");
  RequirePositive(o.coarse_step_m, "coarse_step_m");
  RequirePositive(o.truncation_m, "truncation_m");
  RequirePositive(o.rank_truncation_m, "rank_truncation_m");
  RequirePositive(o.distinct_distance_m, "distinct_distance_m");
  RequirePositive(o.distinct_heading_rad, "distinct_heading_rad");
  // A lattice finer than the field, or a heading step that makes millions of
  // headings, would take hours and gigabytes instead of a second.
  if (!(o.coarse_step_m >= o.grid_resolution_m))
    throw std::invalid_argument(
        "global localiser option coarse_step_m must be at least grid_resolution_m");
  const double cells_per_step = o.coarse_step_m / o.grid_resolution_m;
  if (std::abs(cells_per_step - std::round(cells_per_step)) > 1e-6 * cells_per_step)
    throw std::invalid_argument(
        "global localiser option coarse_step_m must be a whole number of grid_resolution_m "
        "cells (the coarse search looks points up by whole cells)");
  if (!(o.coarse_heading_step_rad >= 1e-3 && o.coarse_heading_step_rad <= geometry::kPi))
    throw std::invalid_argument(
        "global localiser option coarse_heading_step_rad must lie in [0.001, pi]");
  if (!(o.grid_margin_m >= 0.0) || !(o.min_range_m >= 0.0) || !(o.clearance_m >= 0.0) ||
      !(o.coarse_blur_m >= 0.0) || !(o.see_through_margin_m >= 0.0))
    throw std::invalid_argument(
        "global localiser options grid_margin_m, min_range_m, clearance_m, coarse_blur_m and "
        "see_through_margin_m must not be negative");
  if (!(o.min_range_m < o.max_range_m))
    throw std::invalid_argument("global localiser option min_range_m must be below max_range_m");
  // Without a least score or margin every scan would be "found", also where
  // the map explains nothing or two poses explain it equally well.
  if (!(o.min_score > 0.0 && o.min_score <= 1.0))
    throw std::invalid_argument("global localiser option min_score must lie in (0, 1]");
  if (!(o.ambiguity_margin > 0.0 && o.ambiguity_margin < 1.0))
    throw std::invalid_argument("global localiser option ambiguity_margin must lie in (0, 1)");
  if (!(o.refine_precision_m > 0.0 && o.refine_precision_m < 0.5 * o.coarse_step_m))
    throw std::invalid_argument(
        "global localiser option refine_precision_m must lie between 0 and half of coarse_step_m "
        "(the refinement's first step)");
  if (o.coarse_points > 256)
    throw std::invalid_argument(
        "global localiser option coarse_points must be at most 256 (a coarse score sums one "
        "16-bit gain a point, exactly only up to 256 points)");
  if (o.coarse_points > o.max_points)
    throw std::invalid_argument(
        "global localiser option coarse_points must not exceed max_points (the coarse search "
        "uses some of the refinement's points)");
  if (o.max_points < 3 || o.coarse_points < 3 || o.min_points < 3 || o.rank_points < 3 ||
      o.coarse_keep < 1 || o.ranked < 2)
    throw std::invalid_argument(
        "global localiser options max_points, coarse_points, rank_points and min_points must be "
        "at least 3, coarse_keep at least 1 and ranked at least 2");
}

// The map's surfaces in pieces of at most `piece_m` (a wall's piece, or a
// pillar's outline): for each, `visit(lo, hi, distance)` with the piece's
// bounding box and the exact distance from a point to it.
template <typename Visit>
void ForEachSurfacePiece(const world_model::WorldModel& world, double piece_m, Visit&& visit) {
  for (const auto& wall : world.Walls()) {
    const int n = std::max(1, static_cast<int>(std::ceil(wall.Length() / piece_m)));
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d a = wall.a + (wall.b - wall.a) * (double(i) / n);
      const Eigen::Vector2d b = wall.a + (wall.b - wall.a) * (double(i + 1) / n);
      const Eigen::Vector2d ab = b - a;
      const double length2 = ab.squaredNorm();
      visit(a.cwiseMin(b), a.cwiseMax(b), [a, ab, length2](const Eigen::Vector2d& p) {
        const double u = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
        return (a + u * ab - p).norm();
      });
    }
  }
  for (const auto& pillar : world.Cylinders()) {
    const Eigen::Vector2d reach(pillar.radius, pillar.radius);
    visit(pillar.centre - reach, pillar.centre + reach, [&pillar](const Eigen::Vector2d& p) {
      return std::abs((p - pillar.centre).norm() - pillar.radius);
    });
  }
}

// Exact distances from the cell centres (x0 + (c + 0.5) res, y0 + (r + 0.5)
// res) to the nearest wall or pillar outline, where that is within `band`
// (elsewhere: infinity). The distance transform measures from the centres of
// the cells a surface was drawn into, up to half a cell off the surface, and
// in a direction that depends on where the surface falls in its cell: a
// hall's east and west walls were then biased differently, so that a pose
// and its twin (the hall turned by 180 deg) did not fit alike.
std::vector<float> NearSurfaceDistances(const world_model::WorldModel& world, double x0, double y0,
                                        int width, int height, double res, double band) {
  std::vector<float> near(static_cast<size_t>(width) * height,
                          std::numeric_limits<float>::infinity());
  const double piece_m = 1.0;  // a long diagonal wall: the boxes of its pieces, not its own
  ForEachSurfacePiece(world, piece_m, [&](const auto& lo, const auto& hi, const auto& to_piece) {
    const int c0 = std::max(0, static_cast<int>(std::floor((lo.x() - band - x0) / res - 0.5)));
    const int r0 = std::max(0, static_cast<int>(std::floor((lo.y() - band - y0) / res - 0.5)));
    const int c1 = std::min(width - 1, static_cast<int>(std::ceil((hi.x() + band - x0) / res)));
    const int r1 = std::min(height - 1, static_cast<int>(std::ceil((hi.y() + band - y0) / res)));
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        const double d = to_piece(Eigen::Vector2d(x0 + (c + 0.5) * res, y0 + (r + 0.5) * res));
        float& cell = near[static_cast<size_t>(r) * width + c];
        if (d <= band && d < cell) cell = static_cast<float>(d);
      }
    }
  });
  return near;
}

}  // namespace

const char* ToString(GlobalDecision decision) {
  switch (decision) {
    case GlobalDecision::kFound:
      return "found";
    case GlobalDecision::kAmbiguous:
      return "ambiguous";
    case GlobalDecision::kNotFound:
      return "not found";
  }
  return "?";
}

Readings OneScan(std::vector<Eigen::Vector2d> points) {
  Readings readings;
  readings.points = std::move(points);
  return readings;
}

std::vector<Eigen::Vector2d> ScanPointsInLaserFrame(const std::vector<float>& ranges,
                                                    double angle_min, double angle_increment,
                                                    double min_range_m, double max_range_m) {
  std::vector<Eigen::Vector2d> points;
  for (size_t i = 0; i < ranges.size(); ++i) {
    const double r = ranges[i];
    if (!std::isfinite(r) || r < min_range_m || r > max_range_m) continue;
    const double a = angle_min + static_cast<double>(i) * angle_increment;
    points.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return points;
}

GlobalLocaliser::GlobalLocaliser(const world_model::WorldModel& world,
                                 const GlobalLocaliserOptions& options)
    : options_(options) {
  Check(options);
  const double res = options.grid_resolution_m;
  const Eigen::Vector4d bounds = world.Bounds();
  // A margin of whole cells: the coarse lattice (from the map's bounds, whole
  // cells apart) then starts on a cell corner, and a point's cell at a
  // lattice position is that position's cell plus the point's offset in cells.
  const double margin = std::ceil(options.grid_margin_m / res - 1e-9) * res;
  cells_.x0 = bounds[0] - margin;
  cells_.y0 = bounds[1] - margin;
  // Cells up to and including the one holding the far bound (also with no margin).
  const double columns = std::floor((bounds[2] + margin - cells_.x0) / res) + 1;
  const double rows = std::floor((bounds[3] + margin - cells_.y0) / res) + 1;
  if (!(columns * rows <= kMaxCells))
    throw std::invalid_argument(
        "global localiser: the map needs a distance field of more than 50 million cells; "
        "choose a coarser grid_resolution_m");
  cells_.width = std::max(1, static_cast<int>(columns));
  cells_.height = std::max(1, static_cast<int>(rows));

  // Walls and pillar outlines drawn at a quarter-cell spacing.
  cv::Mat image(cells_.height, cells_.width, CV_8U, cv::Scalar(255));
  auto mark = [&](const Eigen::Vector2d& p) {
    const int c = static_cast<int>(std::floor((p.x() - cells_.x0) / res));
    const int r = static_cast<int>(std::floor((p.y() - cells_.y0) / res));
    if (c >= 0 && r >= 0 && c < cells_.width && r < cells_.height) image.at<uchar>(r, c) = 0;
  };
  for (const auto& p : world_model::OutlinePoints(world, 0.25 * res, 16)) mark(p);
  cv::Mat distance;
  cv::distanceTransform(image, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  // The gains depend on distances up to the coarse field's blur plus the
  // truncation only: there (and a cell beyond, where the transform may
  // measure short) they are measured exactly.
  const double band =
      options.coarse_blur_m + std::max(options.truncation_m, options.rank_truncation_m) + res;
  const auto near =
      NearSurfaceDistances(world, cells_.x0, cells_.y0, cells_.width, cells_.height, res, band);

  const size_t count = static_cast<size_t>(cells_.width) * static_cast<size_t>(cells_.height);
  fine_gain_.resize(count);
  rank_gain_.resize(count);
  coarse_gain_.resize(count);
  wall_distance_.resize(count);
  const double t = options.truncation_m, tr = options.rank_truncation_m;
  for (int r = 0; r < cells_.height; ++r) {
    for (int c = 0; c < cells_.width; ++c) {
      const size_t i = static_cast<size_t>(r) * cells_.width + c;
      const double d = std::isfinite(near[i]) ? near[i] : distance.at<float>(r, c) * res;
      const double fine = std::min(d, t),
                   coarse = std::min(std::max(0.0, d - options.coarse_blur_m), t);
      fine_gain_[i] = static_cast<float>(1.0 - fine * fine / (t * t));
      const double sharp = std::min(d, tr);
      rank_gain_[i] = static_cast<float>(1.0 - sharp * sharp / (tr * tr));
      coarse_gain_[i] = ToCoarseGain(1.0 - coarse * coarse / (t * t));
      wall_distance_[i] =
          static_cast<uint8_t>(std::min(255.0f, std::floor(distance.at<float>(r, c))));
    }
  }

  // Coarse candidate positions: a lattice over the map's bounds, clear of walls.
  const double step = options.coarse_step_m;
  const int steps_x = static_cast<int>(std::floor((bounds[2] - bounds[0]) / step));
  const int steps_y = static_cast<int>(std::floor((bounds[3] - bounds[1]) / step));
  lattice_.x0 = bounds[0];
  lattice_.y0 = bounds[1];
  lattice_.rows = steps_y + 1;
  lattice_.columns = steps_x + 1;
  lattice_.position.assign(static_cast<size_t>(lattice_.rows) * lattice_.columns, -1);
  cv::Mat clear(lattice_.rows, lattice_.columns, CV_8U, cv::Scalar(0));
  for (int j = 0; j <= steps_y; ++j) {
    for (int i = 0; i <= steps_x; ++i) {
      const double x = bounds[0] + i * step, y = bounds[1] + j * step;
      const int c = static_cast<int>(std::floor((x - cells_.x0) / res));
      const int r = static_cast<int>(std::floor((y - cells_.y0) / res));
      if (c < 0 || r < 0 || c >= cells_.width || r >= cells_.height) continue;
      if (distance.at<float>(r, c) * res < options.clearance_m) continue;
      lattice_.position[static_cast<size_t>(j) * lattice_.columns + i] =
          static_cast<int>(positions_.size());
      positions_.emplace_back(x, y);
      clear.at<uchar>(j, i) = 1;
    }
  }
  cv::Mat positions_before;
  cv::integral(clear, positions_before, CV_32S);
  lattice_.positions_before.assign(positions_before.begin<int>(), positions_before.end<int>());
  const int step_cells = static_cast<int>(std::lround(step / res));
  coarse_bounds_ =
      CoarseBounds(coarse_gain_, cells_.width, cells_.height, step_cells, kCoarseBoundLevels);
  // The search looks a position's cell up as the nearest cell corner; the
  // lattice starts on one and steps whole cells.
  const int first_column = static_cast<int>(std::lround((lattice_.x0 - cells_.x0) / res));
  const int first_row = static_cast<int>(std::lround((lattice_.y0 - cells_.y0) / res));
  for (int j = 0; j < lattice_.rows; ++j) {
    for (int i = 0; i < lattice_.columns; ++i) {
      const int k = lattice_.position[static_cast<size_t>(j) * lattice_.columns + i];
      if (k < 0) continue;
      const auto& p = positions_[static_cast<size_t>(k)];
      if (std::lround((p.x() - cells_.x0) / res) != first_column + step_cells * i ||
          std::lround((p.y() - cells_.y0) / res) != first_row + step_cells * j)
        throw std::logic_error("global localiser: lattice position " + std::to_string(k) +
                               " is not a whole number of cells from the first");
    }
  }
  phase_gains_.emplace_back(coarse_gain_, cells_.width, cells_.height, step_cells, first_column,
                            first_row);
  for (int level = 1; level <= coarse_bounds_.Levels(); ++level) {
    const int reach = coarse_bounds_.Reach(level);
    phase_gains_.emplace_back(coarse_bounds_.Grid(level), coarse_bounds_.Columns(level),
                              coarse_bounds_.Rows(level), (1 << level) * step_cells,
                              first_column + reach, first_row + reach);
  }
}

// Every `step`-th of the points, at most `most` of them, spread over the scan.
std::vector<Eigen::Vector2d> GlobalLocaliser::Spread(const std::vector<Eigen::Vector2d>& points,
                                                     int most) {
  if (points.size() <= static_cast<size_t>(most)) return points;
  std::vector<Eigen::Vector2d> out;
  const double step = static_cast<double>(points.size()) / most;
  for (int i = 0; i < most; ++i) out.push_back(points[static_cast<size_t>(i * step)]);
  return out;
}

// The same for readings and the places they were seen from (none: all from
// the laser's origin); which of them were the newest scan's is not kept.
Readings GlobalLocaliser::Spread(const Readings& readings, int most) {
  Readings spread = OneScan(Spread(readings.points, most));
  if (!readings.seen_from.empty()) spread.seen_from = Spread(readings.seen_from, most);
  spread.scans = readings.scans;
  return spread;
}

double GlobalLocaliser::Gain(const std::vector<float>& gain, double x, double y) const {
  return GainAtCell(gain, (x - cells_.x0) / options_.grid_resolution_m - 0.5,
                    (y - cells_.y0) / options_.grid_resolution_m - 0.5);
}

double GlobalLocaliser::GainAtCell(const std::vector<float>& gain, double gx, double gy) const {
  if (!(gx >= 0.0 && gy >= 0.0)) return 0.0;
  const int c = static_cast<int>(gx), r = static_cast<int>(gy);  // floor, as not negative
  if (c + 1 >= cells_.width || r + 1 >= cells_.height) return 0.0;
  const double fx = gx - c, fy = gy - r;
  const size_t i = static_cast<size_t>(r) * cells_.width + c;
  const size_t w = static_cast<size_t>(cells_.width);
  const double bottom = (1 - fx) * gain[i] + fx * gain[i + 1];
  const double top = (1 - fx) * gain[i + w] + fx * gain[i + w + 1];
  return (1 - fy) * bottom + fy * top;
}

Readings GlobalLocaliser::UsableReadings(const Readings& readings) const {
  if (!readings.seen_from.empty() && readings.seen_from.size() != readings.points.size())
    throw std::invalid_argument("global localiser: readings have " +
                                std::to_string(readings.points.size()) + " points but " +
                                std::to_string(readings.seen_from.size()) + " places seen from");
  if (readings.newest_points && *readings.newest_points > readings.points.size())
    throw std::invalid_argument("global localiser: readings' newest scan has more points (" +
                                std::to_string(*readings.newest_points) + ") than all (" +
                                std::to_string(readings.points.size()) + ")");
  Readings usable;
  for (size_t i = 0; i < readings.points.size(); ++i) {
    const Eigen::Vector2d& from =
        readings.seen_from.empty() ? Eigen::Vector2d::Zero() : readings.seen_from[i];
    const double r = (readings.points[i] - from).norm();
    if (!std::isfinite(r) || r < options_.min_range_m || r > options_.max_range_m) continue;
    usable.points.push_back(readings.points[i]);
    if (!readings.seen_from.empty()) usable.seen_from.push_back(from);
  }
  return Spread(usable, options_.rank_points);
}

void GlobalLocaliser::TurnPoints(const std::vector<Eigen::Vector2d>& points, double theta,
                                 std::vector<Eigen::Vector2d>& turned) const {
  const double per_cell = 1.0 / options_.grid_resolution_m;
  const double c = std::cos(theta) * per_cell, s = std::sin(theta) * per_cell;
  turned.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    turned[i] = {c * points[i].x() - s * points[i].y(), s * points[i].x() + c * points[i].y()};
  }
}

double GlobalLocaliser::TurnedScore(const std::vector<float>& gain,
                                    const std::vector<Eigen::Vector2d>& turned, double x, double y,
                                    uint64_t* work) const {
  if (work != nullptr) *work += turned.size();
  if (turned.empty()) return 0.0;
  const double per_cell = 1.0 / options_.grid_resolution_m;
  const double gx = (x - cells_.x0) * per_cell - 0.5, gy = (y - cells_.y0) * per_cell - 0.5;
  double sum = 0.0;
  for (const auto& q : turned) sum += GainAtCell(gain, gx + q.x(), gy + q.y());
  return sum / static_cast<double>(turned.size());
}

bool GlobalLocaliser::CrossesWall(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const {
  const WallDistanceField field{&wall_distance_, cells_.width, cells_.height,
                                cells_.x0,       cells_.y0,    options_.grid_resolution_m};
  return localisation_core::CrossesWall(field, from, to);
}

double GlobalLocaliser::RankGain(const Eigen::Vector2d& origin, const Eigen::Vector2d& q) const {
  // A point no surface explains adds nothing, whether its beam crossed a wall or not.
  const double gain = Gain(rank_gain_, q.x(), q.y());
  if (gain <= 0.0) return 0.0;
  return SeenThroughWall(origin, q) ? 0.0 : gain;
}

bool GlobalLocaliser::SeenThroughWall(const Eigen::Vector2d& origin,
                                      const Eigen::Vector2d& q) const {
  const double range = (q - origin).norm();
  if (range <= options_.see_through_margin_m) return false;
  const Eigen::Vector2d short_end =
      origin + (q - origin) * ((range - options_.see_through_margin_m) / range);
  return CrossesWall(origin, short_end);
}

double GlobalLocaliser::ExplainedShare(const std::vector<Eigen::Vector2d>& points,
                                       const geometry::Pose2D& pose,
                                       std::vector<BeamVerdict>& verdicts) const {
  if (points.empty()) return 0.0;
  verdicts.resize(points.size(), BeamVerdict::kUnknown);
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  double sum = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points[i];
    const Eigen::Vector2d q(pose.x + c * p.x() - s * p.y(), pose.y + s * p.x() + c * p.y());
    const double gain = Gain(rank_gain_, q.x(), q.y());
    if (gain <= 0.0) continue;
    if (verdicts[i] == BeamVerdict::kUnknown) {
      verdicts[i] =
          SeenThroughWall(pose.Translation(), q) ? BeamVerdict::kBlocked : BeamVerdict::kClear;
    }
    if (verdicts[i] == BeamVerdict::kClear) sum += gain;
  }
  return sum / static_cast<double>(points.size());
}

double GlobalLocaliser::RankScore(const std::vector<Eigen::Vector2d>& points,
                                  const std::vector<Eigen::Vector2d>& seen_from,
                                  const geometry::Pose2D& pose) const {
  if (points.empty()) return 0.0;
  double sum = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d origin =
        seen_from.empty() ? pose.Translation() : pose.Apply(seen_from[i]);
    sum += RankGain(origin, pose.Apply(points[i]));
  }
  return sum / static_cast<double>(points.size());
}

std::vector<Eigen::Vector2d> GlobalLocaliser::FitPoints(const std::vector<Eigen::Vector2d>& points,
                                                        int most) const {
  return Spread(UsableReadings(OneScan(points)).points, std::max(1, most));
}

geometry::Pose2D GlobalLocaliser::Polish(const std::vector<Eigen::Vector2d>& fit_points,
                                         const geometry::Pose2D& laser_pose) const {
  auto climb =
      StartClimb(rank_gain_, fit_points, laser_pose, 0.05, 0.01, kPolishPrecisionM, nullptr);
  while (!climb.Done()) ClimbRound(rank_gain_, fit_points, climb, nullptr);
  return climb.pose;
}

GlobalLocaliser::Fit GlobalLocaliser::FitAt(const std::vector<Eigen::Vector2d>& fit_points,
                                            const geometry::Pose2D& laser_pose,
                                            double unexplained_likelihood) const {
  Fit fit;
  if (fit_points.empty()) return fit;
  const double u = std::clamp(unexplained_likelihood, 1e-6, 1.0);
  for (const auto& p : fit_points) {
    const double gain = RankGain(laser_pose.Translation(), laser_pose.Apply(p));
    fit.share += gain;
    fit.mean_log_likelihood += std::log((1.0 - u) * gain + u);
  }
  const double n = static_cast<double>(fit_points.size());
  fit.share /= n;
  fit.mean_log_likelihood /= n;
  return fit;
}

double GlobalLocaliser::Score(const std::vector<Eigen::Vector2d>& points,
                              const geometry::Pose2D& laser_pose) const {
  return Score(OneScan(points), laser_pose);
}

double GlobalLocaliser::Score(const Readings& readings, const geometry::Pose2D& laser_pose) const {
  const Readings usable = UsableReadings(readings);
  return RankScore(usable.points, usable.seen_from, laser_pose);
}

// A window's poses: the refinement may climb a coarse step beyond its edge,
// no farther (a pose found far outside was never weighed against the rest of
// the map).
bool GlobalLocaliser::InWindow(const geometry::Pose2D& pose, const SearchWindow& window) const {
  return (pose.Translation() - window.centre.Translation()).norm() <=
             window.radius_m + options_.coarse_step_m &&
         std::abs(geometry::WrapAngle(pose.theta - window.centre.theta)) <=
             window.heading_rad + options_.coarse_heading_step_rad;
}

GlobalLocaliser::Climb GlobalLocaliser::StartClimb(const std::vector<float>& gain,
                                                   const std::vector<Eigen::Vector2d>& points,
                                                   const geometry::Pose2D& pose, double step,
                                                   double turn, double precision_m,
                                                   uint64_t* work) const {
  Climb climb{pose, 0.0, step, turn, precision_m, {}, {}};
  TurnPoints(points, pose.theta, climb.turned);
  climb.score = TurnedScore(gain, climb.turned, pose.x, pose.y, work);
  return climb;
}

// One round of hill climbing: a move of one step in x, y or heading wherever
// it raises the score, the steps halved when none does.
void GlobalLocaliser::ClimbRound(const std::vector<float>& gain,
                                 const std::vector<Eigen::Vector2d>& points, Climb& climb,
                                 uint64_t* work) const {
  bool improved = false;
  const double step = climb.step, turn = climb.turn;
  const Eigen::Vector2d shifts[4] = {{step, 0}, {-step, 0}, {0, step}, {0, -step}};
  for (const auto& shift : shifts) {
    const double x = climb.pose.x + shift.x(), y = climb.pose.y + shift.y();
    const double s = TurnedScore(gain, climb.turned, x, y, work);
    if (s > climb.score) {
      climb.score = s;
      climb.pose.x = x;
      climb.pose.y = y;
      improved = true;
    }
  }
  for (const double sign : {1.0, -1.0}) {
    const double theta = geometry::WrapAngle(climb.pose.theta + sign * turn);
    TurnPoints(points, theta, climb.trial_turned);
    const double s = TurnedScore(gain, climb.trial_turned, climb.pose.x, climb.pose.y, work);
    if (s > climb.score) {
      climb.score = s;
      climb.pose.theta = theta;
      climb.turned.swap(climb.trial_turned);
      improved = true;
    }
  }
  if (!improved) {
    climb.step *= 0.5;
    climb.turn *= 0.5;
  }
}

std::vector<size_t> GlobalLocaliser::PositionsNear(const Eigen::Vector2d& centre,
                                                   double radius_m) const {
  std::vector<size_t> near;
  const double step = options_.coarse_step_m;
  auto first = [&](double from, double origin) {
    return std::max(0, static_cast<int>(std::floor((from - origin) / step)));
  };
  auto last = [&](double to, double origin, int count) {
    return std::min(count - 1, static_cast<int>(std::ceil((to - origin) / step)));
  };
  const int first_column = first(centre.x() - radius_m, lattice_.x0);
  const int last_column = last(centre.x() + radius_m, lattice_.x0, lattice_.columns);
  const int last_row = last(centre.y() + radius_m, lattice_.y0, lattice_.rows);
  for (int j = first(centre.y() - radius_m, lattice_.y0); j <= last_row; ++j) {
    for (int i = first_column; i <= last_column; ++i) {
      const int k = lattice_.position[static_cast<size_t>(j) * lattice_.columns + i];
      if (k >= 0 && (positions_[static_cast<size_t>(k)] - centre).norm() <= radius_m)
        near.push_back(static_cast<size_t>(k));
    }
  }
  return near;
}

}  // namespace structloc::localisation_core
