// Visibility options from the scan's geometry (see header).
#include "structloc/localisation_core/expectation/scan_visibility.hpp"

#include <algorithm>
#include <cmath>

namespace structloc::localisation_core {

world_model::VisibilityOptions ScanVisibility(const LocaliserOptions& options,
                                              const ScanView& scan) {
  world_model::VisibilityOptions o;
  // The same limits as RangeGate (prefilter.cpp).
  o.min_range_m = std::max(options.prefilter.min_range_m, scan.range_min);
  o.max_range_m = scan.range_max > 0.0 ? std::min(options.prefilter.max_range_m, scan.range_max)
                                       : options.prefilter.max_range_m;
  if (!scan.WrapsAround() && scan.count > 0) {
    const double first = scan.angle_min;
    const double last = scan.angle_min + static_cast<double>(scan.count - 1) * scan.angle_increment;
    o.view_min_rad = std::min(first, last);
    o.view_max_rad = std::max(first, last);
  }
  o.min_visible_length_m = options.visibility.min_visible_length_m;
  o.max_incidence_rad = options.visibility.max_incidence_rad;
  return o;
}

bool SameView(const world_model::VisibilityOptions& a, const world_model::VisibilityOptions& b) {
  return a.min_range_m == b.min_range_m && a.max_range_m == b.max_range_m &&
         a.view_min_rad == b.view_min_rad && a.view_max_rad == b.view_max_rad &&
         a.sample_spacing_m == b.sample_spacing_m &&
         a.min_visible_length_m == b.min_visible_length_m &&
         a.max_incidence_rad == b.max_incidence_rad && a.occlusion_margin_m == b.occlusion_margin_m;
}

}  // namespace structloc::localisation_core
