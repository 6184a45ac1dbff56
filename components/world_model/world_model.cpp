// WorldModel validation and corner derivation.
#include "structloc/world_model/world_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "structloc/world_model/point_grid.hpp"

namespace structloc::world_model {
namespace {

bool Finite(const Eigen::Vector2d& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y());
}

void RequireWithin(const Eigen::Vector2d& v, const WorldLimits& limits, const std::string& what) {
  if (std::abs(v.x()) <= limits.max_abs_coordinate_m &&
      std::abs(v.y()) <= limits.max_abs_coordinate_m) {
    return;
  }
  std::ostringstream msg;
  msg << what << " lies beyond " << limits.max_abs_coordinate_m
      << " m from the map origin (is the map in millimetres?)";
  throw std::invalid_argument(msg.str());
}

template <class T>
void RequireUniqueIds(const std::vector<T>& items, const char* kind) {
  std::set<int> ids;
  for (const auto& item : items) {
    if (!ids.insert(item.id).second) {
      throw std::invalid_argument(std::string("duplicate ") + kind + " id " +
                                  std::to_string(item.id));
    }
  }
}

}  // namespace

Wall MakeWall(int id, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  Wall w;
  w.id = id;
  w.a = a;
  w.b = b;
  if ((b - a).norm() > 0.0) w.line = geometry::LineThrough(a, b);
  return w;
}

WorldModel::WorldModel(std::string name, std::vector<Wall> walls, std::vector<Corner> corners,
                       std::vector<Cylinder> cylinders, const CornerDerivation& derivation,
                       const WorldLimits& limits)
    : name_(std::move(name)),
      walls_(std::move(walls)),
      corners_(std::move(corners)),
      cylinders_(std::move(cylinders)) {
  if (walls_.empty() && corners_.empty() && cylinders_.empty()) {
    throw std::invalid_argument("the world has no walls, corners or cylinders");
  }
  if (walls_.size() > limits.max_walls) {
    throw std::invalid_argument("the world has " + std::to_string(walls_.size()) +
                                " walls, more than the limit of " +
                                std::to_string(limits.max_walls) + " walls per map");
  }
  for (auto& w : walls_) {
    if (!Finite(w.a) || !Finite(w.b)) {
      throw std::invalid_argument("wall " + std::to_string(w.id) + " has a non-finite end");
    }
    RequireWithin(w.a, limits, "wall " + std::to_string(w.id));
    RequireWithin(w.b, limits, "wall " + std::to_string(w.id));
    if (w.Length() < 1e-3) {
      throw std::invalid_argument("wall " + std::to_string(w.id) + " has zero length");
    }
    w.line = geometry::LineThrough(w.a, w.b);
  }
  for (const auto& c : corners_) {
    if (!Finite(c.position)) {
      throw std::invalid_argument("corner " + std::to_string(c.id) + " is not finite");
    }
    RequireWithin(c.position, limits, "corner " + std::to_string(c.id));
  }
  for (const auto& c : cylinders_) {
    if (!Finite(c.centre) || !std::isfinite(c.radius)) {
      throw std::invalid_argument("cylinder " + std::to_string(c.id) + " is not finite");
    }
    RequireWithin(c.centre, limits, "cylinder " + std::to_string(c.id));
    if (!(c.radius > 0.0)) {
      throw std::invalid_argument("cylinder " + std::to_string(c.id) + " has radius <= 0");
    }
    if (c.radius > limits.max_radius_m) {
      std::ostringstream msg;
      msg << "cylinder " << c.id << " has a radius above " << limits.max_radius_m << " m";
      throw std::invalid_argument(msg.str());
    }
  }
  RequireUniqueIds(walls_, "wall");
  RequireUniqueIds(corners_, "corner");
  RequireUniqueIds(cylinders_, "cylinder");
  if (!(derivation.join_tolerance_m >= 0.0 && derivation.join_tolerance_m <= 1.0) ||
      !std::isfinite(derivation.angle_tolerance_rad)) {
    throw std::invalid_argument("corner derivation: join tolerance must be 0..1 m");
  }
  DeriveCorners(derivation);
}

// A corner wherever ends of two walls meet (closer than the join tolerance) at
// 90 +- the angle tolerance, unless a corner is already there. Wall pairs are
// visited in the order (i, j > i) so that derived ids do not depend on the
// index; a grid over wall ends and corners finds the candidates.
void WorldModel::DeriveCorners(const CornerDerivation& derivation) {
  const double tolerance = derivation.join_tolerance_m;
  const double cell_size = std::max(tolerance, 1e-3);
  PointGrid wall_ends(cell_size);
  for (size_t i = 0; i < walls_.size(); ++i) {
    wall_ends.Insert(walls_[i].a, i);
    wall_ends.Insert(walls_[i].b, i);
  }
  PointGrid known_corners(cell_size);
  for (size_t k = 0; k < corners_.size(); ++k) known_corners.Insert(corners_[k].position, k);

  long long next_id = 0;  // 64-bit: a given corner may carry the largest int id
  for (const auto& c : corners_) next_id = std::max(next_id, c.id + 1LL);
  const double min_sin = std::cos(derivation.angle_tolerance_rad);  // |sin(angle)| >= cos(tol)
  std::vector<size_t> partners;
  for (size_t i = 0; i < walls_.size(); ++i) {
    partners.clear();
    for (const auto& end : {walls_[i].a, walls_[i].b}) {
      wall_ends.ForEachNear(end, [&](size_t j) {
        if (j > i) partners.push_back(j);
      });
    }
    std::sort(partners.begin(), partners.end());
    partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
    for (const size_t j : partners) {
      const Eigen::Vector2d di = (walls_[i].b - walls_[i].a).normalized();
      const Eigen::Vector2d dj = (walls_[j].b - walls_[j].a).normalized();
      if (std::abs(di.x() * dj.y() - di.y() * dj.x()) < min_sin) continue;
      for (const auto& pi : {walls_[i].a, walls_[i].b}) {
        for (const auto& pj : {walls_[j].a, walls_[j].b}) {
          if ((pi - pj).norm() > tolerance) continue;
          const Eigen::Vector2d p = 0.5 * (pi + pj);
          bool known = false;
          known_corners.ForEachNear(p, [&](size_t k) {
            known = known || (corners_[k].position - p).norm() <= tolerance;
          });
          if (known) continue;
          if (next_id > std::numeric_limits<int>::max()) {
            throw std::invalid_argument("corner ids leave no room for derived corners");
          }
          known_corners.Insert(p, corners_.size());
          corners_.push_back({static_cast<int>(next_id++), p, true});
        }
      }
    }
  }
}

Eigen::Vector4d WorldModel::Bounds() const {
  Eigen::Vector4d b(INFINITY, INFINITY, -INFINITY, -INFINITY);
  auto grow = [&b](const Eigen::Vector2d& p, double margin) {
    b[0] = std::min(b[0], p.x() - margin);
    b[1] = std::min(b[1], p.y() - margin);
    b[2] = std::max(b[2], p.x() + margin);
    b[3] = std::max(b[3], p.y() + margin);
  };
  for (const auto& w : walls_) {
    grow(w.a, 0);
    grow(w.b, 0);
  }
  for (const auto& c : corners_) grow(c.position, 0);
  for (const auto& c : cylinders_) grow(c.centre, c.radius);
  return b;
}

}  // namespace structloc::world_model
