// What the scan at hand can show: its own angular range (from the LaserScan
// message or the log line) and the range limits the prefilter applies to it
// decide which model features are expected (thesis 3.5.3), so
// one parameter file serves 180, 270 and 360 degree scanners alike.
#pragma once

#include "structloc/localisation_core/localiser/localiser_options.hpp"
#include "structloc/localisation_core/scan/scan_points.hpp"
#include "structloc/world_model/visibility.hpp"

namespace structloc::localisation_core {

// Range limits as the prefilter's range gate applies them (the stricter of the
// options and the scan's own), the bearings of the scan's first and last beam
// (a full circle when the scan wraps around), and the visibility settings.
world_model::VisibilityOptions ScanVisibility(const LocaliserOptions& options,
                                              const ScanView& scan);

// True when the two describe the same view, so that a visibility computed for
// one holds for the other.
bool SameView(const world_model::VisibilityOptions& a, const world_model::VisibilityOptions& b);

}  // namespace structloc::localisation_core
