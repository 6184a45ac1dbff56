// Expected walls (see header).
#include "structloc/localisation_core/expectation/expected_walls.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace structloc::localisation_core {

std::vector<WallLineModel> GroupCollinearWalls(const world_model::WorldModel& world,
                                               double r_tolerance_m, double alpha_tolerance_rad) {
  std::vector<WallLineModel> lines;
  for (size_t i = 0; i < world.Walls().size(); ++i) {
    const auto& w = world.Walls()[i];
    bool grouped = false;
    for (auto& l : lines) {
      // Both ends on the group's line (a small angle over a long distance is
      // a large offset), and the same direction.
      const Eigen::Vector2d n(l.c, l.s);
      if (std::abs(n.dot(w.a) - l.line.r) <= r_tolerance_m &&
          std::abs(n.dot(w.b) - l.line.r) <= r_tolerance_m &&
          std::abs(geometry::WrapAngle(l.line.alpha - w.line.alpha)) <= alpha_tolerance_rad) {
        l.walls.push_back(static_cast<int>(i));
        grouped = true;
        break;
      }
    }
    if (!grouped) {
      lines.push_back(
          {w.line, {static_cast<int>(i)}, w.id, std::cos(w.line.alpha), std::sin(w.line.alpha)});
    }
  }
  return lines;
}

void ExpectedWalls::Reserve(size_t l, size_t w) {
  walls.reserve(l);
  extents.reserve(w);
  first_extent_.reserve(l + 1);
  next_.reserve(l);
  sorted_.reserve(w);
}

void ComputeExpectedWalls(const world_model::WorldModel& world,
                          const std::vector<WallLineModel>& lines,
                          const std::vector<int>& wall_line_of,
                          const world_model::Visibility& visibility, const geometry::Pose2D& pose,
                          ExpectedWalls& out) {
  out.walls.clear();
  out.extents.clear();
  for (const auto& vw : visibility.walls) {
    const int line_index = wall_line_of[static_cast<size_t>(vw.index)];
    const auto& model = lines[static_cast<size_t>(line_index)];
    const double cw = model.c, sw = model.s;
    const double t1 = -sw * vw.first.x() + cw * vw.first.y();
    const double t2 = -sw * vw.last.x() + cw * vw.last.y();
    const auto& wall = world.Walls()[static_cast<size_t>(vw.index)];
    const double centre = 0.5 * (-sw * (wall.a.x() + wall.b.x()) + cw * (wall.a.y() + wall.b.y()));
    ExpectedWall* existing = nullptr;
    for (auto& e : out.walls) {
      if (e.line_index == line_index) existing = &e;
    }
    const int index = existing != nullptr ? static_cast<int>(existing - out.walls.data())
                                          : static_cast<int>(out.walls.size());
    out.extents.push_back({index, std::min(t1, t2), std::max(t1, t2), centre, 0.5 * wall.Length()});
    if (existing != nullptr) continue;
    ExpectedWall e;
    e.line_index = line_index;
    e.model_id = model.model_id;
    e.slot = line_index;
    e.world = model.line;
    e.world_c = cw;
    e.world_s = sw;
    e.r = model.line.r - (pose.x * cw + pose.y * sw);
    const double a = model.line.alpha - pose.theta;
    e.c = std::cos(a);
    e.s = std::sin(a);
    out.walls.push_back(e);
  }
  out.IndexExtents();
}

void ExpectedWalls::IndexExtents() {
  // A counting sort: stable, and without allocating once reserved.
  first_extent_.assign(walls.size() + 1, 0);
  for (const auto& x : extents) {
    if (x.expected_index < 0 || static_cast<size_t>(x.expected_index) >= walls.size()) {
      throw std::out_of_range("ExpectedWalls: an extent of expected wall " +
                              std::to_string(x.expected_index) + ", of " +
                              std::to_string(walls.size()));
    }
    ++first_extent_[static_cast<size_t>(x.expected_index) + 1];
  }
  for (size_t e = 0; e < walls.size(); ++e) first_extent_[e + 1] += first_extent_[e];
  sorted_.resize(extents.size());
  next_.assign(first_extent_.begin(), first_extent_.end() - 1);
  for (const auto& x : extents) sorted_[static_cast<size_t>(next_[x.expected_index]++)] = x;
  extents.swap(sorted_);
}

}  // namespace structloc::localisation_core
