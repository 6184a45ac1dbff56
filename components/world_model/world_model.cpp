// WorldModel validation and corner derivation.
#include "world_model.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

namespace structloc::world {
namespace {

bool Finite(const Eigen::Vector2d& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y());
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
                       std::vector<Cylinder> cylinders, const CornerDerivation& derivation)
    : name_(std::move(name)),
      walls_(std::move(walls)),
      corners_(std::move(corners)),
      cylinders_(std::move(cylinders)) {
  if (walls_.empty() && corners_.empty() && cylinders_.empty()) {
    throw std::invalid_argument("the world has no walls, corners or cylinders");
  }
  for (auto& w : walls_) {
    if (!Finite(w.a) || !Finite(w.b)) {
      throw std::invalid_argument("wall " + std::to_string(w.id) + " has a non-finite end");
    }
    if (w.Length() < 1e-3) {
      throw std::invalid_argument("wall " + std::to_string(w.id) + " has zero length");
    }
    w.line = geometry::LineThrough(w.a, w.b);
  }
  for (const auto& c : corners_) {
    if (!Finite(c.position)) {
      throw std::invalid_argument("corner " + std::to_string(c.id) + " is not finite");
    }
  }
  for (const auto& c : cylinders_) {
    if (!Finite(c.centre) || !std::isfinite(c.radius)) {
      throw std::invalid_argument("cylinder " + std::to_string(c.id) + " is not finite");
    }
    if (!(c.radius > 0.0)) {
      throw std::invalid_argument("cylinder " + std::to_string(c.id) + " has radius <= 0");
    }
  }
  RequireUniqueIds(walls_, "wall");
  RequireUniqueIds(corners_, "corner");
  RequireUniqueIds(cylinders_, "cylinder");

  int next_id = 0;
  for (const auto& c : corners_) next_id = std::max(next_id, c.id + 1);
  const double min_sin = std::cos(derivation.angle_tolerance_rad);  // |sin(angle)| >= cos(tol)
  for (size_t i = 0; i < walls_.size(); ++i) {
    for (size_t j = i + 1; j < walls_.size(); ++j) {
      const Eigen::Vector2d di = (walls_[i].b - walls_[i].a).normalized();
      const Eigen::Vector2d dj = (walls_[j].b - walls_[j].a).normalized();
      if (std::abs(di.x() * dj.y() - di.y() * dj.x()) < min_sin) continue;
      for (const auto& pi : {walls_[i].a, walls_[i].b}) {
        for (const auto& pj : {walls_[j].a, walls_[j].b}) {
          if ((pi - pj).norm() > derivation.join_tolerance_m) continue;
          const Eigen::Vector2d p = 0.5 * (pi + pj);
          bool known = false;
          for (const auto& c : corners_) {
            known = known || (c.position - p).norm() <= derivation.join_tolerance_m;
          }
          if (!known) corners_.push_back({next_id++, p, true});
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

}  // namespace structloc::world
