// Shared wall geometry of the map makers (see header).
#include "structloc/map_building/wall_fitting.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "structloc/fitting/line_fit.hpp"

namespace structloc::map_building {

FittedWall FitWall(const std::vector<Eigen::Vector2d>& points) {
  if (points.size() < 2) throw std::invalid_argument("a wall needs at least two points");
  const Eigen::Vector2d origin = points.front();
  fitting::LineSums sums;
  for (const auto& p : points) sums.Add(p.x() - origin.x(), p.y() - origin.y());
  const auto fit = fitting::FitLine(sums, origin.x(), origin.y());
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

// Whether an end of `a` and an end of `b` lie within `reach` of each other.
bool EndsWithin(const FittedWall& a, const FittedWall& b, double reach) {
  const double r2 = reach * reach;
  return (a.a - b.a).squaredNorm() <= r2 || (a.a - b.b).squaredNorm() <= r2 ||
         (a.b - b.a).squaredNorm() <= r2 || (a.b - b.b).squaredNorm() <= r2;
}

// The walls by the square cells (at least the reach wide) their ends lie in,
// kept up to date as ends move: a wall end within reach of a point lies in
// one of the 3 x 3 cells around it. Without it every pair of walls was tried,
// and a noisy 800 x 800 grid's tens of thousands of walls took minutes.
class WallEndCells {
 public:
  WallEndCells(const std::vector<FittedWall>& walls, double cell) : cell_(cell) {
    for (size_t i = 0; i < walls.size(); ++i) {
      Add(i, walls[i].a);
      Add(i, walls[i].b);
    }
  }
  void Add(size_t wall, const Eigen::Vector2d& end) { cells_[Key(end, 0, 0)].push_back(wall); }
  // Returns whether the end changed cells.
  bool Move(size_t wall, const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
    if (Key(from, 0, 0) == Key(to, 0, 0)) return false;
    auto& in = cells_[Key(from, 0, 0)];
    const auto entry = std::find(in.begin(), in.end(), wall);
    if (entry != in.end()) in.erase(entry);  // always there: every move comes through here
    Add(wall, to);
    return true;
  }
  // The walls above `after` with an end in a cell next to an end of `wall`
  // (a or b), in ascending order.
  void Near(const FittedWall& wall, size_t after, std::vector<size_t>& out) const {
    out.clear();
    for (const Eigen::Vector2d* end : {&wall.a, &wall.b}) {
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          const auto found = cells_.find(Key(*end, dx, dy));
          if (found == cells_.end()) continue;
          for (size_t w : found->second)
            if (w > after) out.push_back(w);
        }
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

 private:
  std::pair<long long, long long> Key(const Eigen::Vector2d& p, int dx, int dy) const {
    return {Index(p.x()) + dx, Index(p.y()) + dy};
  }
  // A coordinate's cell; far beyond any map (a malformed grid's origin) all
  // coordinates share the outermost cells, and NaN one of its own.
  long long Index(double coordinate) const {
    const double q = std::floor(coordinate / cell_);
    if (std::isnan(q)) return 0;
    return static_cast<long long>(std::clamp(q, -1e18, 1e18));
  }
  double cell_;
  std::map<std::pair<long long, long long>, std::vector<size_t>> cells_;
};

}  // namespace

bool JoinWallEnds(FittedWall& first, FittedWall& second, const CornerJoinOptions& options) {
  if (!EndsWithin(first, second, 2.0 * options.max_end_distance_m + 1e-9)) return false;
  const double angle = std::abs(std::sin(first.line.alpha - second.line.alpha));
  if (angle < std::sin(options.min_angle_rad)) return false;
  Eigen::Vector2d at;
  if (!Intersect(first.line, second.line, at)) return false;
  double d1 = 0.0, d2 = 0.0;
  Eigen::Vector2d& end_1 = NearerEnd(first, at, d1);
  Eigen::Vector2d& end_2 = NearerEnd(second, at, d2);
  if (d1 > options.max_end_distance_m || d2 > options.max_end_distance_m) return false;
  // Only ends: the intersection must not lie deep inside either wall.
  const double t1 = AlongWall(first, at), t2 = AlongWall(second, at);
  const double l1 = first.Length(), l2 = second.Length();
  const double slack = options.max_end_distance_m;
  if (!(t1 < slack || t1 > l1 - slack) || !(t2 < slack || t2 > l2 - slack)) return false;
  end_1 = at;
  end_2 = at;
  return true;
}

size_t JoinCorners(std::vector<FittedWall>& walls, const CornerJoinOptions& options) {
  size_t joined = 0;
  // Cells a little wider than the reach, so that rounding far from the
  // origin cannot put two ends within reach two cells apart.
  WallEndCells cells(walls, 1.01 * (2.0 * options.max_end_distance_m + 1e-9));
  // The pairs (i, j > i) in the order of a double loop over all pairs, each
  // tried with the ends as earlier joins left them; only pairs with ends
  // within reach can join, and the cells give those.
  std::vector<size_t> near;
  for (size_t i = 0; i < walls.size(); ++i) {
    cells.Near(walls[i], i, near);
    size_t k = 0;
    while (k < near.size()) {
      const size_t j = near[k++];
      const FittedWall before_i = walls[i], before_j = walls[j];
      if (!JoinWallEnds(walls[i], walls[j], options)) continue;
      ++joined;
      const bool a_changed_cells = cells.Move(i, before_i.a, walls[i].a);
      const bool b_changed_cells = cells.Move(i, before_i.b, walls[i].b);
      cells.Move(j, before_j.a, walls[j].a);
      cells.Move(j, before_j.b, walls[j].b);
      // Wall i's end moved to another cell: the walls after j near its ends
      // now. (Within its cell the walls near it are the same, but for j,
      // which is done with.)
      if (a_changed_cells || b_changed_cells) {
        cells.Near(walls[i], j, near);
        k = 0;
      }
    }
  }
  return joined;
}

size_t DropShortWalls(std::vector<FittedWall>& walls, double min_length_m) {
  const auto kept = std::remove_if(walls.begin(), walls.end(), [min_length_m](const FittedWall& w) {
    return w.Length() < min_length_m;
  });
  const auto dropped = static_cast<size_t>(walls.end() - kept);
  walls.erase(kept, walls.end());
  return dropped;
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
