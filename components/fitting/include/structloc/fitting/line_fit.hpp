// The thesis' least-squares line (3.5.2, EQ 18/20) from running sums of a
// point set: total least squares, no trigonometry in the fit (the normal
// (cos alpha, sin alpha) comes from the half-angle identities of EQ 20). The
// localiser fits every sliding window of a scan with it, map making every
// segment and wall of a recording.
#pragma once

#include <algorithm>
#include <cmath>

namespace structloc::fitting {

// Running sums of a point set, relative to an origin (ox, oy) chosen near the
// points to keep cancellation small.
struct LineSums {
  double n = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  void Add(double x, double y) {
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    syy += y * y;
    sxy += x * y;
  }
  void Remove(double x, double y) {
    n -= 1;
    sx -= x;
    sy -= y;
    sxx -= x * x;
    syy -= y * y;
    sxy -= x * y;
  }
};

// A fitted line: x cos(alpha) + y sin(alpha) = r with r >= 0.
struct LineEstimate {
  double r = 0.0;
  double cos_alpha = 1.0;
  double sin_alpha = 0.0;
  double sse = 0.0;           // sum of squared perpendicular residuals
  double along_spread = 0.0;  // sum of squared deviations along the line
  double xm = 0.0;            // centroid
  double ym = 0.0;
  bool degenerate = true;  // points have no preferred direction (or n < 2)
  double Alpha() const { return std::atan2(sin_alpha, cos_alpha); }
  // Perpendicular distance of (x, y) from the line.
  double DistanceTo(double x, double y) const {
    return std::abs(x * cos_alpha + y * sin_alpha - r);
  }
};

// The centroid of a point set and its second moments about it (EQ 20's
// Suu, Svv, Suv).
struct LineMoments {
  double xm = 0.0, ym = 0.0;
  double suu = 0.0, svv = 0.0, suv = 0.0;
};

// The moments of the summed points (n >= 1); (ox, oy) is the origin the sums
// were taken relative to, the centroid is in the original frame. `inv_n` is
// 1 / s.n (given, where many sums of one count are fitted).
inline LineMoments Moments(const LineSums& s, double ox, double oy, double inv_n) {
  const double mx = s.sx * inv_n, my = s.sy * inv_n;
  LineMoments m;
  m.xm = mx + ox;
  m.ym = my + oy;
  m.suu = std::max(0.0, s.sxx - s.sx * mx);
  m.svv = std::max(0.0, s.syy - s.sy * my);
  m.suv = s.sxy - s.sx * my;
  return m;
}

// Total least squares line from the moments: two square roots and one
// division, and no branch (selects only) to mispredict from one sliding
// window to the next.
inline LineEstimate FitMoments(const LineMoments& m) {
  LineEstimate e;
  // EQ 20: alpha = 1/2 atan2(-2 Suv, Svv - Suu), via cos/sin of 2 alpha.
  const double a = -2.0 * m.suv, b = m.svv - m.suu;
  const double h = std::sqrt(a * a + b * b);
  e.xm = m.xm;
  e.ym = m.ym;
  e.sse = std::max(0.0, 0.5 * (m.suu + m.svv - h));
  e.along_spread = 0.5 * (m.suu + m.svv + h);
  // (Below 1e-140, 2 h (h + |b|) further down could underflow to 0.)
  e.degenerate = !(h > 1e-140);
  // EQ 20's half angle without trigonometry: (cos alpha, sin alpha) is parallel
  // to (h + b, a) and to (a, h - b); the one without cancellation is taken,
  // normalised by its length sqrt(2 h (h + |b|)), with cos alpha >= 0.
  const double u = h + std::abs(b);
  const double k = 1.0 / std::sqrt(2.0 * h * u);
  const double abs_a = std::abs(a), signed_u = std::copysign(u, a);
  const bool b_positive = b >= 0.0;
  const double c0 = (b_positive ? u : abs_a) * k;
  const double s0 = (b_positive ? a : signed_u) * k;
  const double r0 = e.xm * c0 + e.ym * s0;    // EQ 18
  const double flip = r0 < 0.0 ? -1.0 : 1.0;  // r >= 0: the normal points away
  const double r = flip * r0, c = flip * c0, sn = flip * s0;
  e.r = e.degenerate ? 0.0 : r;
  e.cos_alpha = e.degenerate ? 1.0 : c;
  e.sin_alpha = e.degenerate ? 0.0 : sn;
  return e;
}

// Total least squares line of the summed points; (ox, oy) is the origin the
// sums were taken relative to, the result is in the original frame.
inline LineEstimate FitLine(const LineSums& s, double ox, double oy) {
  if (s.n < 2) return LineEstimate{};
  return FitMoments(Moments(s, ox, oy, 1.0 / s.n));
}

}  // namespace structloc::fitting
