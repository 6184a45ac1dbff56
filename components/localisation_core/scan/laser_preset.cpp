// The laser preset chosen from a scan's geometry (see header).
#include "structloc/localisation_core/scan/laser_preset.hpp"

#include <cmath>
#include <initializer_list>
#include <sstream>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::localisation_core {

namespace {

bool NearIncrement(double increment_deg, std::initializer_list<double> choices_deg) {
  for (const double c : choices_deg) {
    if (std::abs(increment_deg - c) <= 0.03 * c) return true;
  }
  return false;
}

}  // namespace

LaserPresetChoice ChooseLaserPreset(const ScanShape& shape) {
  const double increment_deg = std::abs(shape.angle_increment_rad) * 180.0 / geometry::kPi;
  const double fov_deg =
      shape.beams > 1 ? static_cast<double>(shape.beams - 1) * increment_deg : 0.0;
  const bool range_known = std::isfinite(shape.range_max_m) && shape.range_max_m > 0.0;
  std::ostringstream seen;
  seen.precision(3);
  seen << shape.beams << " beams over " << fov_deg << " deg at " << increment_deg << " deg, "
       << (range_known ? "reaching " : "maximum range not given");
  if (range_known) seen << shape.range_max_m << " m";
  LaserPresetChoice choice;
  if (fov_deg >= 95.0 && fov_deg <= 185.0 && NearIncrement(increment_deg, {0.25, 0.5, 1.0}) &&
      (!range_known || shape.range_max_m >= 8.0)) {
    choice.file = "maps/params/sick_lms2xx.xml";
    choice.reason = seen.str() + ": a SICK LMS 2xx (100 or 180 deg at 0.25-1 deg, 8-80 m)";
  } else if (fov_deg >= 265.0 && fov_deg <= 280.0 && NearIncrement(increment_deg, {0.25})) {
    choice.file = "maps/params/hokuyo_utm30lx.xml";
    choice.reason = seen.str() + ": a Hokuyo UTM-30LX (270 deg at 0.25 deg)";
  } else if (fov_deg >= 265.0 && fov_deg <= 280.0 && NearIncrement(increment_deg, {0.5})) {
    choice.file = "maps/params/sick_s300_microscan3.xml";
    choice.reason = seen.str() + ": a SICK S300 or microScan3 (270-275 deg at 0.5 deg)";
  } else {
    choice.reason = seen.str() +
                    ": no shipped preset matches, so the built-in defaults (the thesis' Table 6); "
                    "give --params for your laser";
  }
  return choice;
}

std::string DescribeChoice(const LaserPresetChoice& choice) {
  return (choice.file.empty() ? std::string("built-in defaults") : choice.file) +
         ", chosen from the first scan (" + choice.reason + ")";
}

}  // namespace structloc::localisation_core
