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

// Total least squares line of the summed points; (ox, oy) is the origin the
// sums were taken relative to, the result is in the original frame. Inline:
// the localiser calls it for every sliding window of every scan.
inline LineEstimate FitLine(const LineSums& s, double ox, double oy) {
  LineEstimate e;
  if (s.n < 2) return e;
  const double inv_n = 1.0 / s.n;
  const double mx = s.sx * inv_n, my = s.sy * inv_n;
  const double suu = std::max(0.0, s.sxx - s.sx * mx);
  const double svv = std::max(0.0, s.syy - s.sy * my);
  const double suv = s.sxy - s.sx * my;
  // EQ 20: alpha = 1/2 atan2(-2 Suv, Svv - Suu), via cos/sin of 2 alpha.
  const double a = -2.0 * suv, b = svv - suu;
  const double h = std::sqrt(a * a + b * b);
  e.xm = mx + ox;
  e.ym = my + oy;
  e.sse = std::max(0.0, 0.5 * (suu + svv - h));
  e.along_spread = 0.5 * (suu + svv + h);
  if (!(h > 1e-300)) return e;
  const double cos2 = b / h;
  double c = std::sqrt(std::max(0.0, 0.5 * (1.0 + cos2)));
  double sn = std::copysign(std::sqrt(std::max(0.0, 0.5 * (1.0 - cos2))), a);
  double r = e.xm * c + e.ym * sn;  // EQ 18
  if (r < 0.0) {
    r = -r;
    c = -c;
    sn = -sn;
  }
  e.r = r;
  e.cos_alpha = c;
  e.sin_alpha = sn;
  e.degenerate = false;
  return e;
}

}  // namespace structloc::fitting
