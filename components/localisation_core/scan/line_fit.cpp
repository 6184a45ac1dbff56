// Sliding least-squares line fit (see header).
#include "structloc/localisation_core/scan/line_fit.hpp"

namespace structloc::localisation_core {

void FitWindowLines(const ScanPoints& points, const LineFitOptions& options,
                    std::vector<WindowLine>& out) {
  const size_t n = points.Size();
  const size_t o = static_cast<size_t>(options.window_points);
  if (n < o) {
    out.clear();
    return;
  }
  const size_t windows = points.wraps ? n : n - o + 1;
  out.resize(windows);  // every field of every window is written below
  const double max_sse = options.max_rms_m * options.max_rms_m * static_cast<double>(o);
  const double inv_o = 1.0 / static_cast<double>(o);  // every window holds o points
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
    WindowLine& w = out[i];
    w.line = FitMoments(Moments(sums, ox, oy, inv_o));
    w.first = static_cast<int>(i);
    w.valid = !w.line.degenerate && w.line.sse <= max_sse;
  }
}

}  // namespace structloc::localisation_core
