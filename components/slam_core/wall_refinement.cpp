// Pose-and-wall refinement (see header).
#include "structloc/slam_core/wall_refinement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "pose_graph_problem.hpp"
#include "structloc/map_building/scan_segments.hpp"
#include "structloc/map_building/wall_fitting.hpp"

namespace structloc::slam_core {
namespace {

// A segment in the map frame as the current poses put it, its normal facing
// the laser that saw it (the two faces of a thin wall are different walls).
struct Sighting {
  int keyframe = 0;
  const KeyframeSegment* segment = nullptr;
  Eigen::Vector2d a, b, normal;
};

// A wall of the building: the line normal . p = distance, its extent along
// (-normal.y, normal.x), and the sightings given to it.
struct Wall {
  Eigen::Vector2d normal;
  double distance = 0.0;
  double lo = 0.0, hi = 0.0;
  std::vector<const Sighting*> sightings;
  Eigen::Vector2d Along() const { return {-normal.y(), normal.x()}; }
  // The point of its line `s` along it.
  Eigen::Vector2d At(double s) const { return distance * normal + s * Along(); }
};

Sighting Place(int keyframe, const KeyframeSegment& segment, const geometry::Pose2D& pose) {
  Sighting s;
  s.keyframe = keyframe;
  s.segment = &segment;
  s.a = pose.Apply(segment.a);
  s.b = pose.Apply(segment.b);
  const Eigen::Vector2d d = (s.b - s.a).normalized();
  s.normal = {-d.y(), d.x()};
  if (s.normal.dot(pose.Translation() - s.a) < 0) s.normal = -s.normal;
  return s;
}

// How far the farther of a stretch's ends `a`, `b` lies from the wall's line,
// or a negative number when the stretch does not belong to the wall: it faces
// (`normal`) another way, lies farther than max_offset_m, or neither overlaps
// the wall nor comes within max_gap_m along it.
double StretchOffset(const Wall& wall, const Eigen::Vector2d& normal, const Eigen::Vector2d& a,
                     const Eigen::Vector2d& b, const WallRefinementOptions& o) {
  if (wall.normal.dot(normal) < std::cos(o.max_angle_rad)) return -1;
  const double offset = std::max(std::abs(wall.normal.dot(a) - wall.distance),
                                 std::abs(wall.normal.dot(b) - wall.distance));
  if (offset > o.max_offset_m) return -1;
  const double sa = wall.Along().dot(a), sb = wall.Along().dot(b);
  if (std::min(sa, sb) > wall.hi + o.max_gap_m || std::max(sa, sb) < wall.lo - o.max_gap_m)
    return -1;
  return offset;
}

// Whether `other`'s stretch of wall lies on `wall`.
bool SameWall(const Wall& wall, const Wall& other, const WallRefinementOptions& o) {
  return StretchOffset(wall, other.normal, other.At(other.lo), other.At(other.hi), o) >= 0;
}

// Walls begun apart (a sighting's wall grows only as far as the sightings
// given to it so far reach) joined where they turn out to be one.
void JoinWalls(std::vector<Wall>& walls, const WallRefinementOptions& options) {
  for (bool joined = true; joined;) {
    joined = false;
    for (size_t i = 0; i < walls.size(); ++i) {
      for (size_t j = i + 1; j < walls.size();) {
        if (!SameWall(walls[i], walls[j], options)) {
          ++j;
          continue;
        }
        // The other's ends projected on this wall's direction, as a sighting's are.
        for (const double s : {walls[j].lo, walls[j].hi}) {
          const double t = walls[i].Along().dot(walls[j].At(s));
          walls[i].lo = std::min(walls[i].lo, t);
          walls[i].hi = std::max(walls[i].hi, t);
        }
        walls[i].sightings.insert(walls[i].sightings.end(), walls[j].sightings.begin(),
                                  walls[j].sightings.end());
        walls.erase(walls.begin() + static_cast<long>(j));
        joined = true;
      }
    }
  }
}

// Greedy association, longest sightings first: each joins the wall it lies
// nearest to, else starts one; then walls that are one are joined, so a wall
// driven past twice ties both passes (a loop closure, hence the Cauchy loss).
std::vector<Wall> Associate(const std::vector<Sighting>& sightings,
                            const WallRefinementOptions& options) {
  std::vector<size_t> order(sightings.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t i, size_t j) {
    return (sightings[i].b - sightings[i].a).squaredNorm() >
           (sightings[j].b - sightings[j].a).squaredNorm();
  });
  std::vector<Wall> walls;
  for (size_t i : order) {
    const Sighting& s = sightings[i];
    Wall* best = nullptr;
    double best_offset = INFINITY;
    for (auto& w : walls) {
      const double offset = StretchOffset(w, s.normal, s.a, s.b, options);
      if (offset >= 0 && offset < best_offset) {
        best = &w;
        best_offset = offset;
      }
    }
    if (!best) {
      walls.push_back({s.normal, s.normal.dot(s.a), 0, 0, {}});
      best = &walls.back();
      best->lo = best->hi = best->Along().dot(s.a);
    }
    for (const auto& end : {s.a, s.b}) {
      best->lo = std::min(best->lo, best->Along().dot(end));
      best->hi = std::max(best->hi, best->Along().dot(end));
    }
    best->sightings.push_back(&s);
  }
  JoinWalls(walls, options);
  return walls;
}

// A wall's line through all its sightings' ends, its normal kept facing the
// same way.
std::array<double, 2> FitLine(const Wall& wall) {
  std::vector<Eigen::Vector2d> ends;
  for (const auto* s : wall.sightings) {
    ends.push_back(s->a);
    ends.push_back(s->b);
  }
  const auto fitted = map_building::FitWall(ends);
  Eigen::Vector2d normal(std::cos(fitted.line.alpha), std::sin(fitted.line.alpha));
  double distance = fitted.line.r;
  if (normal.dot(wall.normal) < 0) {
    normal = -normal;
    distance = -distance;
  }
  return {std::atan2(normal.y(), normal.x()), distance};
}

bool SeenTwice(const Wall& wall) {
  for (const auto* s : wall.sightings)
    if (s->keyframe != wall.sightings.front()->keyframe) return true;
  return false;
}

// A segment end (keyframe frame) against its wall's line (angle of the
// normal, distance): the distance across, in standard deviations.
struct WallEndError {
  Eigen::Vector2d a, b;
  double inv_sigma;

  template <typename T>
  bool operator()(const T* const pose, const T* const wall, T* residual) const {
    const T c = ceres::cos(pose[2]), s = ceres::sin(pose[2]);
    const T nx = ceres::cos(wall[0]), ny = ceres::sin(wall[0]);
    const Eigen::Vector2d* ends[2] = {&a, &b};
    for (int i = 0; i < 2; ++i) {
      const T x = c * T(ends[i]->x()) - s * T(ends[i]->y()) + pose[0];
      const T y = s * T(ends[i]->x()) + c * T(ends[i]->y()) + pose[1];
      residual[i] = (nx * x + ny * y - wall[1]) * T(inv_sigma);
    }
    return true;
  }
};

double EndSigma(const KeyframeSegment& s, const WallRefinementOptions& o) {
  // A fitted line's offset has variance rms^2 / n at the centroid and its
  // ends, half a length away, about four times that.
  const double independent = std::max(1.0, static_cast<double>(s.points) / o.correlated_points);
  return std::max(o.min_sigma_m, 2.0 * s.rms_m / std::sqrt(independent));
}

}  // namespace

std::vector<KeyframeSegment> FindKeyframeSegments(const std::vector<Eigen::Vector2d>& points) {
  std::vector<KeyframeSegment> out;
  for (const auto& range : map_building::ExtractScanSegments(points, {})) {
    const std::vector<Eigen::Vector2d> run(points.begin() + static_cast<long>(range.first),
                                           points.begin() + static_cast<long>(range.last));
    const auto fitted = map_building::FitWall(run);
    out.push_back({fitted.a, fitted.b, fitted.rms_m, fitted.points});
  }
  return out;
}

WallRefinementSummary RefineWithWalls(std::vector<geometry::Pose2D>& poses,
                                      const std::vector<std::vector<KeyframeSegment>>& segments,
                                      const std::vector<PoseGraphEdge>& edges,
                                      const WallRefinementOptions& options,
                                      const PoseGraphOptions& graph) {
  if (segments.size() != poses.size())
    throw std::invalid_argument("wall refinement: segments of " + std::to_string(segments.size()) +
                                " keyframes for " + std::to_string(poses.size()) + " poses");
  WallRefinementSummary summary;
  if (poses.size() < 2) return summary;
  for (int round = 0; round < options.rounds; ++round) {
    std::vector<Sighting> sightings;
    for (size_t k = 0; k < poses.size(); ++k)
      for (const auto& s : segments[k])
        sightings.push_back(Place(static_cast<int>(k), s, poses[k]));
    const std::vector<Wall> walls = Associate(sightings, options);
    internal::PoseBlocks x = internal::ToBlocks(poses);
    std::vector<std::array<double, 2>> lines;  // Ceres keeps their addresses: reserved
    lines.reserve(walls.size());
    ceres::Problem problem;
    internal::AddEdges(edges, graph, problem, x);
    summary.walls = summary.observations = 0;
    for (const auto& wall : walls) {
      if (!SeenTwice(wall)) continue;
      lines.push_back(FitLine(wall));
      ++summary.walls;
      for (const auto* s : wall.sightings) {
        ++summary.observations;
        auto* cost = new ceres::AutoDiffCostFunction<WallEndError, 2, 3, 2>(
            new WallEndError{s->segment->a, s->segment->b, 1.0 / EndSigma(*s->segment, options)});
        problem.AddResidualBlock(cost, new ceres::CauchyLoss(options.robust_scale_sigmas),
                                 x[s->keyframe].data(), lines.back().data());
      }
    }
    const auto result = internal::Solve(graph, problem, x);
    summary.usable = summary.usable && result.IsSolutionUsable();
    internal::FromBlocks(x, poses);
  }
  return summary;
}

}  // namespace structloc::slam_core
