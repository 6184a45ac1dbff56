// Merging collinear pieces of one wall (see header).
#include "structloc/map_building/collinear_merging.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::map_building {
namespace {

// Union-find over wall indices.
class Classes {
 public:
  explicit Classes(size_t n) : parent_(n) {
    for (size_t i = 0; i < n; ++i) parent_[i] = i;
  }
  size_t Find(size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void Join(size_t i, size_t j) {
    i = Find(i);
    j = Find(j);
    if (i != j) parent_[std::max(i, j)] = std::min(i, j);
  }

 private:
  std::vector<size_t> parent_;
};

// Direction in [-bucket/2, pi - bucket/2) and the offset of a wall's line, so
// that nearly horizontal walls share a bucket whichever way they were drawn.
constexpr double kAngleBucketRad = 0.01;
constexpr double kOffsetBucketM = 0.05;

Eigen::Vector2d CanonicalDirection(const world_model::Wall& w) {
  Eigen::Vector2d d = (w.b - w.a).normalized();
  double theta = std::atan2(d.y(), d.x());
  if (theta < 0.0) theta += geometry::kPi;
  if (theta >= geometry::kPi - kAngleBucketRad / 2) theta -= geometry::kPi;
  return {std::cos(theta), std::sin(theta)};
}

// True when w and v lie on one line (each one's ends within `tolerance` of the
// other's line) and touch or overlap along it within `tolerance`.
bool Continues(const world_model::Wall& w, const world_model::Wall& v, double tolerance) {
  const auto off_line = [tolerance](const world_model::Wall& l, const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = (l.b - l.a).normalized();
    const Eigen::Vector2d q = p - l.a;
    return std::abs(d.x() * q.y() - d.y() * q.x()) > tolerance;
  };
  if (off_line(w, v.a) || off_line(w, v.b) || off_line(v, w.a) || off_line(v, w.b)) return false;
  const Eigen::Vector2d d = (w.b - w.a).normalized();
  const double w0 = 0.0, w1 = (w.b - w.a).norm();
  const double v0 = std::min(d.dot(v.a - w.a), d.dot(v.b - w.a));
  const double v1 = std::max(d.dot(v.a - w.a), d.dot(v.b - w.a));
  return v0 <= w1 + tolerance && w0 <= v1 + tolerance;
}

}  // namespace

size_t MergeCollinear(std::vector<world_model::Wall>& walls, double tolerance) {
  if (tolerance <= 0.0 || walls.size() < 2) return 0;
  std::map<std::pair<long long, long long>, std::vector<size_t>> buckets;
  std::vector<std::pair<long long, long long>> keys(walls.size());
  for (size_t i = 0; i < walls.size(); ++i) {
    const Eigen::Vector2d d = CanonicalDirection(walls[i]);
    const double offset = d.x() * walls[i].a.y() - d.y() * walls[i].a.x();
    keys[i] = {std::llround(std::atan2(d.y(), d.x()) / kAngleBucketRad),
               std::llround(offset / kOffsetBucketM)};
    buckets[keys[i]].push_back(i);
  }
  Classes classes(walls.size());
  for (size_t i = 0; i < walls.size(); ++i) {
    for (long long da = -1; da <= 1; ++da) {
      for (long long dr = -1; dr <= 1; ++dr) {
        const auto it = buckets.find({keys[i].first + da, keys[i].second + dr});
        if (it == buckets.end()) continue;
        for (const size_t j : it->second) {
          if (j > i && Continues(walls[i], walls[j], tolerance)) classes.Join(i, j);
        }
      }
    }
  }
  std::map<size_t, std::vector<size_t>> groups;  // first piece -> pieces
  for (size_t i = 0; i < walls.size(); ++i) groups[classes.Find(i)].push_back(i);
  std::vector<world_model::Wall> merged;
  merged.reserve(groups.size());
  for (const auto& [first, pieces] : groups) {
    size_t longest = pieces.front();
    for (const size_t p : pieces) {
      if (walls[p].Length() > walls[longest].Length()) longest = p;
    }
    const world_model::Wall& line = walls[longest];
    const Eigen::Vector2d d = (line.b - line.a).normalized();
    double lo = 0.0, hi = line.Length();
    for (const size_t p : pieces) {
      for (const Eigen::Vector2d& e : {walls[p].a, walls[p].b}) {
        lo = std::min(lo, d.dot(e - line.a));
        hi = std::max(hi, d.dot(e - line.a));
      }
    }
    merged.push_back(world_model::MakeWall(static_cast<int>(merged.size()) + 1, line.a + lo * d,
                                           line.a + hi * d));
  }
  const size_t gone = walls.size() - merged.size();
  walls = std::move(merged);
  return gone;
}

}  // namespace structloc::map_building
