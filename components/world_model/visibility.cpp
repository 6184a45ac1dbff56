// Visibility computation (see header). Occlusion is tested only against the
// surfaces that can hide a target: those within range of the sensor, and for
// each wall those that may cross the triangle between the sensor and the
// wall's part in view. The result is the same as testing every surface of the
// scene, at a fraction of the cost on large maps.
#include "structloc/world_model/visibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace structloc::world_model {
namespace {

// Guard for the sample count of one wall; walls within WorldLimits need at
// most a few million samples at the default spacing.
constexpr double kMaxIntervals = 1e12;
// Surfaces this close to the region a ray may cross are kept as possible
// occluders, so that rounding never drops a real one.
constexpr double kSelectionSlackM = 1e-6;
// Samples of one wall sharing one occluder selection (0.8 m at 5 cm spacing).
constexpr int64_t kStretchSamples = 16;
// Near segments subtending more than this at the sensor are candidates for
// every wall; the others only for walls whose angular span meets theirs.
constexpr double kWideRad = 0.2;
constexpr double kAngleSlackRad = 1e-6;

inline double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

bool FullCircle(const VisibilityOptions& o) {
  return o.view_max_rad - o.view_min_rad >= 2.0 * geometry::kPi - 1e-9;
}

// The scanner's field of view in the map frame, for bearing tests without
// trigonometry: a direction is in view when it lies counter-clockwise from
// `first` by at most the span, which ends at `last`.
struct ViewCone {
  Eigen::Vector2d origin, first, last;
  bool full_circle = false;
  bool reflex = false;  // span above pi: the blind wedge from last to first is below pi
};

ViewCone MakeViewCone(const geometry::Pose2D& sensor, const VisibilityOptions& o) {
  ViewCone cone;
  cone.origin = sensor.Translation();
  cone.full_circle = FullCircle(o);
  const double a = sensor.theta + o.view_min_rad, b = sensor.theta + o.view_max_rad;
  cone.first = {std::cos(a), std::sin(a)};
  cone.last = {std::cos(b), std::sin(b)};
  cone.reflex = o.view_max_rad - o.view_min_rad > geometry::kPi;
  return cone;
}

bool InView(const ViewCone& cone, const Eigen::Vector2d& p, const VisibilityOptions& o) {
  const Eigen::Vector2d d = p - cone.origin;
  const double range_sq = d.squaredNorm();
  if (range_sq < o.min_range_m * o.min_range_m || range_sq > o.max_range_m * o.max_range_m) {
    return false;
  }
  if (cone.full_circle) return true;
  if (cone.reflex) return !(Cross(cone.last, d) > 0.0 && Cross(d, cone.first) > 0.0);
  return Cross(cone.first, d) >= 0.0 && Cross(d, cone.last) >= 0.0;
}

double SquaredDistance(const Eigen::Vector2d& p, const Segment& s) {
  const Eigen::Vector2d e = s.b - s.a;
  const double length_sq = e.squaredNorm();
  const double t = length_sq > 0.0 ? std::clamp((p - s.a).dot(e) / length_sq, 0.0, 1.0) : 0.0;
  return (s.a + t * e - p).squaredNorm();
}

// The separating axes of the triangle (o, p, q) that MayCross tests a
// segment against: each edge with the sign of the inside and its slack,
// computed once for all the segments tested against one triangle.
struct TriangleAxes {
  TriangleAxes(const Eigen::Vector2d& o, const Eigen::Vector2d& p, const Eigen::Vector2d& q)
      : corner{o, p, q} {
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d& u = corner[i];
      edge[i] = corner[(i + 1) % 3] - u;
      const double inside = Cross(edge[i], corner[(i + 2) % 3] - u);
      flat[i] = inside == 0.0;  // a flat triangle: this axis separates nothing
      sign[i] = inside > 0.0 ? 1.0 : -1.0;
      slack[i] = kSelectionSlackM * edge[i].norm();
    }
  }
  Eigen::Vector2d corner[3], edge[3];
  double sign[3], slack[3];
  bool flat[3];
};

// False only when the segment certainly misses the triangle: separating axes
// are the triangle's edge normals and the segment's normal.
bool MayCross(const Segment& s, const TriangleAxes& t) {
  for (int i = 0; i < 3; ++i) {
    if (t.flat[i]) continue;
    const Eigen::Vector2d& u = t.corner[i];
    if (t.sign[i] * Cross(t.edge[i], s.a - u) < -t.slack[i] &&
        t.sign[i] * Cross(t.edge[i], s.b - u) < -t.slack[i]) {
      return false;
    }
  }
  const Eigen::Vector2d e = s.b - s.a;
  const double slack = kSelectionSlackM * e.norm();
  const double c0 = Cross(e, t.corner[0] - s.a), c1 = Cross(e, t.corner[1] - s.a),
               c2 = Cross(e, t.corner[2] - s.a);
  return !((c0 > slack && c1 > slack && c2 > slack) || (c0 < -slack && c1 < -slack && c2 < -slack));
}

// Scene::Occluded restricted to the given segments (and every circle): true
// when one of them lies between origin and target, more than `margin` before it.
bool Hidden(const Scene& scene, const std::vector<int>& segments, const Eigen::Vector2d& origin,
            const Eigen::Vector2d& target, double margin) {
  const Eigen::Vector2d delta = target - origin;
  const double dist = delta.norm();
  if (dist <= margin) return false;
  const Eigen::Vector2d d = delta / dist;
  const double reach = dist - margin;
  // A segment whose bounding box misses the sight line's cannot hide the target.
  const double min_x = std::min(origin.x(), target.x()) - kSelectionSlackM;
  const double min_y = std::min(origin.y(), target.y()) - kSelectionSlackM;
  const double max_x = std::max(origin.x(), target.x()) + kSelectionSlackM;
  const double max_y = std::max(origin.y(), target.y()) + kSelectionSlackM;
  for (int s : segments) {
    const Segment& g = scene.segments[static_cast<size_t>(s)];
    if (std::max(g.a.x(), g.b.x()) < min_x || std::min(g.a.x(), g.b.x()) > max_x ||
        std::max(g.a.y(), g.b.y()) < min_y || std::min(g.a.y(), g.b.y()) > max_y) {
      continue;
    }
    if (RaySegment(origin, d, g) < reach) return true;
  }
  for (const auto& c : scene.circles) {
    if (RayCircle(origin, d, c) < reach) return true;
  }
  return false;
}

// The bearings from o that segment (a, b) covers: [start, start + span], span
// < pi. False when the segment passes (nearly) through o.
bool AngularSpan(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                 double& start, double& span) {
  if (SquaredDistance(o, {a, b}) < 1e-6) return false;
  const double ta = std::atan2(a.y() - o.y(), a.x() - o.x());
  const double tb = std::atan2(b.y() - o.y(), b.x() - o.x());
  const double d = geometry::WrapAngle(tb - ta);
  start = d >= 0.0 ? ta : tb;
  span = std::abs(d);
  return true;
}

// The near segments whose angular span may meet that of the wall part (p, q):
// every wide one, and the narrow ones starting within kWideRad before it.
void AngularCandidates(const Visibility& v, const Eigen::Vector2d& o, const Eigen::Vector2d& p,
                       const Eigen::Vector2d& q, std::vector<int>& out) {
  out.clear();
  double start = 0.0, span = 0.0;
  if (!AngularSpan(o, p, q, start, span)) {
    out.insert(out.end(), v.near_segments.begin(), v.near_segments.end());
    return;
  }
  out.insert(out.end(), v.wide_segments.begin(), v.wide_segments.end());
  auto add = [&](double lo, double hi) {
    auto it = std::lower_bound(v.narrow_segments.begin(), v.narrow_segments.end(),
                               std::make_pair(lo, -1));
    for (; it != v.narrow_segments.end() && it->first <= hi; ++it) out.push_back(it->second);
  };
  const double lo = start - kWideRad - kAngleSlackRad, hi = start + span + kAngleSlackRad;
  constexpr double kTwoPi = 2.0 * geometry::kPi;
  if (lo < -geometry::kPi) {
    add(lo + kTwoPi, kTwoPi);
    add(-kTwoPi, hi);
  } else if (hi > geometry::kPi) {
    add(lo, kTwoPi);
    add(-kTwoPi, hi - kTwoPi);
  } else {
    add(lo, hi);
  }
}

// The segments of `from` that may cross the triangle (o, p, q): bounding boxes
// first (cheap), then the separating axes.
void SelectOccluders(const Scene& scene, const std::vector<int>& from, const Eigen::Vector2d& o,
                     const Eigen::Vector2d& p, const Eigen::Vector2d& q, std::vector<int>& out) {
  out.clear();
  const double min_x = std::min({o.x(), p.x(), q.x()}) - kSelectionSlackM;
  const double min_y = std::min({o.y(), p.y(), q.y()}) - kSelectionSlackM;
  const double max_x = std::max({o.x(), p.x(), q.x()}) + kSelectionSlackM;
  const double max_y = std::max({o.y(), p.y(), q.y()}) + kSelectionSlackM;
  const TriangleAxes triangle(o, p, q);
  for (int s : from) {
    const Segment& g = scene.segments[static_cast<size_t>(s)];
    if (std::max(g.a.x(), g.b.x()) < min_x || std::min(g.a.x(), g.b.x()) > max_x ||
        std::max(g.a.y(), g.b.y()) < min_y || std::min(g.a.y(), g.b.y()) > max_y) {
      continue;
    }
    if (MayCross(g, triangle)) out.push_back(s);
  }
}

}  // namespace

VisibilityOptions VisibilityOptions::Centred(double field_of_view_rad) {
  VisibilityOptions o;
  o.view_min_rad = -0.5 * field_of_view_rad;
  o.view_max_rad = 0.5 * field_of_view_rad;
  return o;
}

void Visibility::Reserve(const WorldModel& world, const Scene& scene) {
  walls.reserve(world.Walls().size());
  corners.reserve(world.Corners().size());
  cylinders.reserve(world.Cylinders().size());
  near_segments.reserve(scene.segments.size());
  narrow_segments.reserve(scene.segments.size());
  wide_segments.reserve(scene.segments.size());
  wall_candidates.reserve(scene.segments.size());
  wall_occluders.reserve(scene.segments.size());
  stretch_occluders.reserve(scene.segments.size());
}

void ComputeVisibility(const WorldModel& world, const Scene& scene, const geometry::Pose2D& sensor,
                       const VisibilityOptions& o, Visibility& result) {
  result.walls.clear();
  result.corners.clear();
  result.cylinders.clear();
  result.near_segments.clear();
  const Eigen::Vector2d origin = sensor.Translation();
  const ViewCone cone = MakeViewCone(sensor, o);
  const double cos_max_incidence = std::cos(o.max_incidence_rad);
  // A surface that hides a target within range crosses the range circle.
  const double reach = o.max_range_m + kSelectionSlackM;
  result.narrow_segments.clear();
  result.wide_segments.clear();
  for (size_t s = 0; s < scene.segments.size(); ++s) {
    const Segment& g = scene.segments[s];
    if (SquaredDistance(origin, g) > reach * reach) continue;
    result.near_segments.push_back(static_cast<int>(s));
    double start = 0.0, span = 0.0;
    if (AngularSpan(origin, g.a, g.b, start, span) && span <= kWideRad) {
      result.narrow_segments.emplace_back(start, static_cast<int>(s));
    } else {
      result.wide_segments.push_back(static_cast<int>(s));
    }
  }
  std::sort(result.narrow_segments.begin(), result.narrow_segments.end());
  for (size_t i = 0; i < world.Walls().size(); ++i) {
    const auto& w = world.Walls()[i];
    const double length = w.Length();
    // Samples k = 0..intervals along the whole wall, counted in 64 bits.
    const double wanted = std::ceil(length / o.sample_spacing_m);
    const int64_t intervals =
        wanted >= 1.0 ? static_cast<int64_t>(std::min(wanted, kMaxIntervals)) : 1;
    // Only samples on the chord of the range circle can be in view: visit
    // those (one extra on each side against rounding), not the whole wall.
    const Eigen::Vector2d along_wall = (w.b - w.a) / length;
    const double along = (origin - w.a).dot(along_wall);
    const double off_line_sq = std::max(0.0, (origin - w.a).squaredNorm() - along * along);
    const double range_sq = o.max_range_m * o.max_range_m;
    if (off_line_sq > range_sq) continue;
    const double half_chord = std::sqrt(range_sq - off_line_sq);
    const double per_metre = static_cast<double>(intervals) / length;
    const auto first_k = static_cast<int64_t>(std::clamp(
        std::floor((along - half_chord) * per_metre) - 1.0, 0.0, static_cast<double>(intervals)));
    const auto last_k = static_cast<int64_t>(std::clamp(
        std::ceil((along + half_chord) * per_metre) + 1.0, 0.0, static_cast<double>(intervals)));
    const Eigen::Vector2d normal(std::cos(w.line.alpha), std::sin(w.line.alpha));
    const double step = length / static_cast<double>(intervals);
    auto sample = [&](int64_t k) -> Eigen::Vector2d {
      return w.a + (w.b - w.a) * (static_cast<double>(k) / static_cast<double>(intervals));
    };
    // In range and view, and not seen too obliquely.
    auto facing = [&](const Eigen::Vector2d& p) {
      return InView(cone, p, o) &&
             std::abs((p - origin).normalized().dot(normal)) >= cos_max_incidence;
    };
    // The first and last such sample span the triangle any hiding surface crosses.
    int64_t lo = -1, hi = -1;
    for (int64_t k = first_k; k <= last_k; ++k) {
      if (!facing(sample(k))) continue;
      if (lo < 0) lo = k;
      hi = k;
    }
    if (lo < 0) continue;
    AngularCandidates(result, origin, sample(lo), sample(hi), result.wall_candidates);
    SelectOccluders(scene, result.wall_candidates, origin, sample(lo), sample(hi),
                    result.wall_occluders);
    VisibleWall vw;
    vw.index = static_cast<int>(i);
    bool any = false;
    for (int64_t k = lo; k <= hi; ++k) {
      // Stretches of kStretchSamples samples, each with its own narrower occluders.
      if ((k - lo) % kStretchSamples == 0) {
        SelectOccluders(scene, result.wall_occluders, origin, sample(k),
                        sample(std::min(hi, k + kStretchSamples - 1)), result.stretch_occluders);
      }
      const Eigen::Vector2d p = sample(k);
      if (!facing(p)) continue;
      if (Hidden(scene, result.stretch_occluders, origin, p, o.occlusion_margin_m)) continue;
      if (!any) vw.first = p;
      vw.last = p;
      vw.visible_length_m += step;
      any = true;
    }
    if (any && vw.visible_length_m >= o.min_visible_length_m) result.walls.push_back(vw);
  }
  for (size_t i = 0; i < world.Corners().size(); ++i) {
    const Eigen::Vector2d p = world.Corners()[i].position;
    if (InView(cone, p, o) &&
        !Hidden(scene, result.near_segments, origin, p, o.occlusion_margin_m)) {
      result.corners.push_back(static_cast<int>(i));
    }
  }
  for (size_t i = 0; i < world.Cylinders().size(); ++i) {
    const auto& c = world.Cylinders()[i];
    const Eigen::Vector2d to_centre = c.centre - origin;
    if (to_centre.norm() <= c.radius) continue;
    const Eigen::Vector2d near = c.centre - c.radius * to_centre.normalized();
    if (InView(cone, near, o) &&
        !Hidden(scene, result.near_segments, origin, near, o.occlusion_margin_m)) {
      result.cylinders.push_back(static_cast<int>(i));
    }
  }
}

}  // namespace structloc::world_model
