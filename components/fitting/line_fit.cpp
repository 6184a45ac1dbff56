// Total least squares line from running sums (see header).
#include "structloc/fitting/line_fit.hpp"

#include <algorithm>

namespace structloc::fitting {

LineEstimate FitLine(const LineSums& s, double ox, double oy) {
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
