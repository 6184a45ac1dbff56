// Ray casting (see header).
#include "structloc/world_model/ray_cast.hpp"

#include <cmath>
#include <limits>

namespace structloc::world_model {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
inline double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}
}  // namespace

Scene Scene::FromWorld(const WorldModel& world) {
  Scene scene;
  for (const auto& w : world.Walls()) scene.segments.push_back({w.a, w.b});
  for (const auto& c : world.Cylinders()) scene.circles.push_back({c.centre, c.radius});
  return scene;
}

void Scene::Add(const Scene& other) {
  segments.insert(segments.end(), other.segments.begin(), other.segments.end());
  circles.insert(circles.end(), other.circles.begin(), other.circles.end());
}

double RaySegment(const Eigen::Vector2d& origin, const Eigen::Vector2d& d, const Segment& s) {
  const Eigen::Vector2d e = s.b - s.a;
  const double denom = Cross(d, e);
  if (std::abs(denom) < 1e-15) return kInf;
  const Eigen::Vector2d ao = s.a - origin;
  const double t = Cross(ao, e) / denom;
  const double u = Cross(ao, d) / denom;
  if (t <= 0.0 || u < 0.0 || u > 1.0) return kInf;
  return t;
}

double RayCircle(const Eigen::Vector2d& origin, const Eigen::Vector2d& d, const Circle& c) {
  const Eigen::Vector2d oc = origin - c.centre;
  const double b = d.dot(oc);
  const double cc = oc.squaredNorm() - c.radius * c.radius;
  const double disc = b * b - cc;
  if (disc < 0.0) return kInf;
  const double root = std::sqrt(disc);
  const double t1 = -b - root;
  if (t1 > 0.0) return t1;
  const double t2 = -b + root;
  return t2 > 0.0 ? t2 : kInf;
}

double Scene::Cast(const Eigen::Vector2d& origin, const Eigen::Vector2d& d,
                   double max_range) const {
  double best = kInf;
  for (const auto& s : segments) best = std::min(best, RaySegment(origin, d, s));
  for (const auto& c : circles) best = std::min(best, RayCircle(origin, d, c));
  return best <= max_range ? best : kInf;
}

bool Scene::Occluded(const Eigen::Vector2d& origin, const Eigen::Vector2d& target,
                     double margin) const {
  const Eigen::Vector2d delta = target - origin;
  const double dist = delta.norm();
  if (dist <= margin) return false;
  return Cast(origin, delta / dist, dist - margin) < dist - margin;
}

}  // namespace structloc::world_model
