// Shared wall geometry of the map makers (see header).
#include "structloc/map_building/wall_fitting.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "structloc/localisation_core/line_fit.hpp"

namespace structloc::map_building {

FittedWall FitWall(const std::vector<Eigen::Vector2d>& points) {
  if (points.size() < 2) throw std::invalid_argument("a wall needs at least two points");
  const Eigen::Vector2d origin = points.front();
  localisation_core::LineSums sums;
  for (const auto& p : points) sums.Add(p.x() - origin.x(), p.y() - origin.y());
  const auto fit = localisation_core::FitLine(sums, origin.x(), origin.y());
  if (fit.degenerate) throw std::invalid_argument("a wall's points are all in one place");
  FittedWall wall;
  wall.line = geometry::Normalised(fit.r, fit.Alpha());
  wall.points = points.size();
  wall.rms_m = std::sqrt(std::max(0.0, fit.sse) / static_cast<double>(points.size()));
  const Eigen::Vector2d normal(std::cos(wall.line.alpha), std::sin(wall.line.alpha));
  const Eigen::Vector2d direction(-normal.y(), normal.x());
  const Eigen::Vector2d foot = wall.line.r * normal;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : points) {
    const double t = direction.dot(p - foot);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  wall.a = foot + lo * direction;
  wall.b = foot + hi * direction;
  return wall;
}

double AlongWall(const FittedWall& wall, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = wall.b - wall.a;
  const double length = d.norm();
  if (length <= 0.0) return 0.0;
  return d.dot(p - wall.a) / length;
}

std::vector<std::vector<Eigen::Vector2d>> SplitAtGaps(const FittedWall& wall,
                                                      const std::vector<Eigen::Vector2d>& points,
                                                      double max_gap_m) {
  std::vector<std::pair<double, Eigen::Vector2d>> ordered;
  ordered.reserve(points.size());
  for (const auto& p : points) ordered.emplace_back(AlongWall(wall, p), p);
  std::sort(ordered.begin(), ordered.end(),
            [](const auto& l, const auto& r) { return l.first < r.first; });
  std::vector<std::vector<Eigen::Vector2d>> runs;
  for (size_t i = 0; i < ordered.size(); ++i) {
    if (i == 0 || ordered[i].first - ordered[i - 1].first > max_gap_m) runs.emplace_back();
    runs.back().push_back(ordered[i].second);
  }
  return runs;
}

namespace {

// Intersection of two lines in Hessian form; false when (nearly) parallel.
bool Intersect(const geometry::Line& l, const geometry::Line& m, Eigen::Vector2d& at) {
  const double det = std::sin(m.alpha - l.alpha);
  if (std::abs(det) < 1e-9) return false;
  at = {(l.r * std::sin(m.alpha) - m.r * std::sin(l.alpha)) / det,
        (m.r * std::cos(l.alpha) - l.r * std::cos(m.alpha)) / det};
  return true;
}

// The end of `wall` nearer to `p` (a or b), and its distance.
Eigen::Vector2d& NearerEnd(FittedWall& wall, const Eigen::Vector2d& p, double& distance) {
  const double da = (wall.a - p).norm(), db = (wall.b - p).norm();
  distance = std::min(da, db);
  return da <= db ? wall.a : wall.b;
}

// Whether an end of `a` and an end of `b` lie within `reach` of each other. A
// corner within max_end_distance_m of an end of each wall needs that with
// twice the distance, so most pairs of a large map are passed over without
// any trigonometry (a noisy 800 x 800 grid gives tens of thousands of walls).
bool EndsWithin(const FittedWall& a, const FittedWall& b, double reach) {
  const double r2 = reach * reach;
  return (a.a - b.a).squaredNorm() <= r2 || (a.a - b.b).squaredNorm() <= r2 ||
         (a.b - b.a).squaredNorm() <= r2 || (a.b - b.b).squaredNorm() <= r2;
}

}  // namespace

size_t JoinCorners(std::vector<FittedWall>& walls, const CornerJoinOptions& options) {
  size_t joined = 0;
  const double reach = 2.0 * options.max_end_distance_m + 1e-9;
  for (size_t i = 0; i < walls.size(); ++i) {
    for (size_t j = i + 1; j < walls.size(); ++j) {
      if (!EndsWithin(walls[i], walls[j], reach)) continue;
      const double angle = std::abs(std::sin(walls[i].line.alpha - walls[j].line.alpha));
      if (angle < std::sin(options.min_angle_rad)) continue;
      Eigen::Vector2d at;
      if (!Intersect(walls[i].line, walls[j].line, at)) continue;
      double di = 0.0, dj = 0.0;
      Eigen::Vector2d& end_i = NearerEnd(walls[i], at, di);
      Eigen::Vector2d& end_j = NearerEnd(walls[j], at, dj);
      if (di > options.max_end_distance_m || dj > options.max_end_distance_m) continue;
      // Only ends: the intersection must not lie deep inside either wall.
      const double ti = AlongWall(walls[i], at), tj = AlongWall(walls[j], at);
      const double li = walls[i].Length(), lj = walls[j].Length();
      const double slack = options.max_end_distance_m;
      const bool near_end_i = ti < slack || ti > li - slack;
      const bool near_end_j = tj < slack || tj > lj - slack;
      if (!near_end_i || !near_end_j) continue;
      end_i = at;
      end_j = at;
      ++joined;
    }
  }
  return joined;
}

world_model::WorldModel MakeWorld(const std::string& name, const std::vector<FittedWall>& walls,
                                  const std::vector<world_model::Cylinder>& cylinders) {
  std::vector<world_model::Wall> model_walls;
  model_walls.reserve(walls.size());
  for (const auto& w : walls) {
    if ((w.b - w.a).norm() < 1e-3) continue;
    model_walls.push_back(
        world_model::MakeWall(static_cast<int>(model_walls.size()) + 1, w.a, w.b));
  }
  std::vector<world_model::Cylinder> model_cylinders = cylinders;
  for (size_t i = 0; i < model_cylinders.size(); ++i)
    model_cylinders[i].id = static_cast<int>(i) + 1;
  return world_model::WorldModel(name, std::move(model_walls), {}, std::move(model_cylinders));
}

}  // namespace structloc::map_building
