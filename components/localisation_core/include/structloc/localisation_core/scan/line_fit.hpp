// Step 2 (thesis 3.5.2, EQ 18/20): a least-squares line through every window of
// `window_points` consecutive points, with sums updated incrementally as the
// window slides (O(1) per window). Each window gives one point in (r, alpha)
// space; windows on one straight wall pile up in a cluster. The hot loop uses
// no trigonometry: the normal (cos alpha, sin alpha) comes from the
// half-angle identities of EQ 20; alpha itself is atan2(sin, cos) on demand.
#pragma once

#include <vector>

#include "structloc/fitting/line_fit.hpp"
#include "structloc/localisation_core/scan/scan_points.hpp"

namespace structloc::localisation_core {

struct LineFitOptions {
  int window_points = 7;    // Table 6: number of elements in line fitting
  double max_rms_m = 0.03;  // windows whose points scatter more than this about their
                            // line (corners, depth jumps, clutter) are not used
};

// The fit itself is the fitting library's (map making uses it too).
using fitting::FitLine;
using fitting::FitMoments;
using fitting::LineEstimate;
using fitting::LineSums;
using fitting::Moments;

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
