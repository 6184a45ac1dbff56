// De-skewing (see header).
#include "structloc/localisation_core/scan/deskew.hpp"

#include <algorithm>
#include <cmath>

namespace structloc::localisation_core {

void BeamMotion::Reserve(size_t n) {
  x.reserve(n);
  y.reserve(n);
  c.reserve(n);
  s.reserve(n);
}

void BeamMotion::Resize(size_t n) {
  x.resize(n);
  y.resize(n);
  c.resize(n);
  s.resize(n);
}

void LinearBeamMotion(const geometry::Pose2D& first_to_last, size_t count, BeamMotion& motion) {
  motion.Resize(count);
  const double steps = count > 1 ? static_cast<double>(count - 1) : 1.0;
  // Rotation by a constant step per beam: cos/sin by recurrence.
  const double dtheta = first_to_last.theta / steps;
  const double cd = std::cos(dtheta), sd = std::sin(dtheta);
  double c = 1.0, s = 0.0;
  for (size_t i = 0; i < count; ++i) {
    const double f = static_cast<double>(i) / steps;
    motion.x[i] = f * first_to_last.x;
    motion.y[i] = f * first_to_last.y;
    motion.c[i] = c;
    motion.s[i] = s;
    const double cn = c * cd - s * sd;
    s = s * cd + c * sd;
    c = cn;
  }
}

bool BeamMotionFromHistory(const OdometryHistory& history, const geometry::Pose2D& mount,
                           double stamp, double time_increment, size_t count, BeamMotion& motion,
                           double max_extrapolation_s) {
  const double last = stamp + time_increment * static_cast<double>(count ? count - 1 : 0);
  const auto base_ref = history.At(stamp);
  if (!base_ref || !history.AtOrExtrapolated(last, max_extrapolation_s)) return false;
  const geometry::Pose2D ref = geometry::Compose(*base_ref, mount);
  const geometry::Pose2D ref_inv = geometry::Inverse(ref);
  motion.Resize(count);
  // The sensor pose is looked up exactly at every kKnotBeams-th beam and at
  // the last; the beams between lie within a fraction of a millisecond, where
  // the odometry moves along a straight line and turns by under a milliradian,
  // so x, y and the rotation's cosine and sine are interpolated linearly (off
  // by well under a micrometre; a lookup per beam cost half of each update).
  constexpr size_t kKnotBeams = 16;
  const auto exact = [&](size_t i) {
    const auto base = history.AtOrExtrapolated(stamp + time_increment * static_cast<double>(i),
                                               max_extrapolation_s);
    const geometry::Pose2D rel = geometry::Compose(ref_inv, geometry::Compose(*base, mount));
    motion.x[i] = rel.x;
    motion.y[i] = rel.y;
    motion.c[i] = std::cos(rel.theta);
    motion.s[i] = std::sin(rel.theta);
  };
  if (count == 0) return true;
  exact(0);
  for (size_t a = 0; a + 1 < count;) {
    const size_t b = std::min(a + kKnotBeams, count - 1);
    exact(b);
    for (size_t i = a + 1; i < b; ++i) {
      const double f = static_cast<double>(i - a) / static_cast<double>(b - a);
      motion.x[i] = motion.x[a] + f * (motion.x[b] - motion.x[a]);
      motion.y[i] = motion.y[a] + f * (motion.y[b] - motion.y[a]);
      motion.c[i] = motion.c[a] + f * (motion.c[b] - motion.c[a]);
      motion.s[i] = motion.s[a] + f * (motion.s[b] - motion.s[a]);
    }
    a = b;
  }
  return true;
}

void Deskew(const BeamMotion& motion, ScanPoints& points) {
  for (size_t k = 0; k < points.Size(); ++k) {
    const size_t b = static_cast<size_t>(points.beam[k]);
    const double px = points.x[k], py = points.y[k];
    points.x[k] = motion.x[b] + motion.c[b] * px - motion.s[b] * py;
    points.y[k] = motion.y[b] + motion.s[b] * px + motion.c[b] * py;
  }
}

}  // namespace structloc::localisation_core
