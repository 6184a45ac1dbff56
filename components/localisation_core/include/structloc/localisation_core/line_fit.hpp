// Step 2 (thesis 3.5.2, EQ 18/20): a least-squares line through every window of
// `window_points` consecutive points, with sums updated incrementally as the
// window slides (O(1) per window). Each window gives one point in (r, alpha)
// space; windows on one straight wall pile up in a cluster. The hot loop uses
// no trigonometry: the normal (cos alpha, sin alpha) comes from the
// half-angle identities of EQ 20; alpha itself is atan2(sin, cos) on demand.
#pragma once

#include <cmath>
#include <vector>

#include "structloc/localisation_core/scan_points.hpp"

namespace structloc::localisation_core {

struct LineFitOptions {
  int window_points = 7;    // Table 6: number of elements in line fitting
  double max_rms_m = 0.03;  // windows whose points scatter more than this about their
                            // line (corners, depth jumps, clutter) are not used
};

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
// sums were taken relative to, the result is in the original frame.
LineEstimate FitLine(const LineSums& sums, double ox, double oy);

struct WindowLine {
  LineEstimate line;
  int first = 0;       // index of the window's first point
  bool valid = false;  // not degenerate and rms within max_rms_m
};

// One WindowLine per window start (n for wrapping scans, n - o + 1 otherwise);
// clears `out` first.
void FitWindowLines(const ScanPoints& points, const LineFitOptions& options,
                    std::vector<WindowLine>& out);

}  // namespace structloc::localisation_core
