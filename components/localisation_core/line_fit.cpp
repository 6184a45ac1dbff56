// Sliding least-squares line fit (see header).
#include "structloc/localisation_core/line_fit.hpp"

namespace structloc::localisation_core {

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

void FitWindowLines(const ScanPoints& points, const LineFitOptions& options,
                    std::vector<WindowLine>& out) {
  out.clear();
  const size_t n = points.Size();
  const size_t o = static_cast<size_t>(options.window_points);
  if (n < o) return;
  const size_t windows = points.wraps ? n : n - o + 1;
  const double max_sse = options.max_rms_m * options.max_rms_m * static_cast<double>(o);
  const double ox = points.x[0], oy = points.y[0];
  LineSums sums;
  for (size_t k = 0; k < o; ++k) sums.Add(points.x[k] - ox, points.y[k] - oy);
  for (size_t i = 0; i < windows; ++i) {
    if (i > 0) {
      const size_t leaving = i - 1;
      const size_t entering = i + o - 1 < n ? i + o - 1 : i + o - 1 - n;
      sums.Remove(points.x[leaving] - ox, points.y[leaving] - oy);
      sums.Add(points.x[entering] - ox, points.y[entering] - oy);
    }
    WindowLine w;
    w.line = FitLine(sums, ox, oy);
    w.first = static_cast<int>(i);
    w.valid = !w.line.degenerate && w.line.sse <= max_sse;
    out.push_back(w);
  }
}

}  // namespace structloc::localisation_core
