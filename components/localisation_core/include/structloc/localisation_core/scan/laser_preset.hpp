// Which shipped laser preset (maps/params/) suits a scan, chosen from the
// scan's own geometry, for a run given no parameter file: the laser's field
// of view, beam spacing and maximum range name its family as well as its
// datasheet does. A user's --params always wins. The default of replay and of
// the localisation component alike (which takes the laser's mounting from
// rt/tf_static, as replay takes it from the log's laser and robot poses). DDS-free.
#pragma once

#include <cstddef>
#include <string>

namespace structloc::localisation_core {

// What a scan says about its laser.
struct ScanShape {
  size_t beams = 0;
  double angle_increment_rad = 0.0;  // sign ignored
  double range_max_m = 0.0;          // 0 or not finite: unknown
};

struct LaserPresetChoice {
  // A file relative to structloc's data folder ("maps/params/sick_lms2xx.xml");
  // empty: no preset matches, the built-in defaults (the thesis' Table 6).
  std::string file;
  std::string reason;  // one sentence: the scan's geometry and why it matched
};

// The rules, first match wins (field of view = (beams - 1) x increment):
//   - 95..185 deg at 0.25, 0.5 or 1 deg, reaching at least 8 m (or unknown):
//     a SICK LMS 2xx (100 or 180 deg; 8 m in mm mode, 80 m in cm mode);
//   - 265..280 deg at 0.25 deg: a Hokuyo UTM-30LX;
//   - 265..280 deg at 0.5 deg: a SICK S300 / microScan3;
//   - anything else: the built-in defaults.
// Increments match within 3 %.
LaserPresetChoice ChooseLaserPreset(const ScanShape& shape);

// One line for the run's summary or log: "<file>, chosen from the first scan
// (<reason>)" ("built-in defaults" when no preset matched).
std::string DescribeChoice(const LaserPresetChoice& choice);

}  // namespace structloc::localisation_core
