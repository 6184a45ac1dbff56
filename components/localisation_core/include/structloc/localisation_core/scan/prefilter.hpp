// Step 1 of the pipeline (thesis 3.4): range gate, rejection of
// unsupported points, thinning. NaN/inf/negative ranges are rejected and
// counted, never propagated.
#pragma once

#include <cstddef>
#include <string>

#include "structloc/localisation_core/scan/scan_points.hpp"

namespace structloc::localisation_core {

struct PrefilterOptions {
  double min_range_m = 0.5;                // Table 6: minimum range
  double max_range_m = 4.0;                // Table 6: maximum range
  double max_neighbour_distance_m = 0.3;   // Table 6: a point farther than this from both
                                           // neighbours is unsupported
  double min_neighbour_distance_m = 0.06;  // Table 6: thinning distance
};

struct PrefilterStats {
  size_t beams = 0;
  size_t non_finite = 0;    // NaN or +-inf (REP-117 special values)
  size_t negative = 0;      // ranges below zero: invalid readings
  size_t out_of_range = 0;  // outside [min, max] of the options and the sensor
  size_t unsupported = 0;
  size_t thinned = 0;
  size_t kept = 0;
};

// Range gate + polar-to-Cartesian (EQ 5). Clears `out` first.
void RangeGate(const ScanView& scan, const BeamDirections& directions,
               const PrefilterOptions& options, ScanPoints& out, PrefilterStats& stats);
// Drops points farther than max_neighbour_distance_m from both neighbours
// (unsupported: a lone return in mid-air), then thins: drops points closer
// than min_neighbour_distance_m to the last point kept. One pass for both.
void RejectUnsupportedAndThin(const PrefilterOptions& options, ScanPoints& points,
                              PrefilterStats& stats);

struct BeamMotion;  // deskew.hpp
// The whole step as the localiser runs it: RangeGate, the points de-skewed by
// `motion` (nullptr: not) before the neighbourhood tests, then
// RejectUnsupportedAndThin. Clears `out` first.
void Prefilter(const ScanView& scan, const BeamDirections& directions,
               const PrefilterOptions& options, const BeamMotion* motion, ScanPoints& out,
               PrefilterStats& stats);

}  // namespace structloc::localisation_core
