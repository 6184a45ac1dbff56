// Paths of the source tree and the built executables, for tests (DDS-free).
#pragma once

#include <string>

namespace structloc::testing {

inline std::string SourcePath(const std::string& relative) {
  return std::string(STRUCTLOC_SOURCE_DIR) + "/" + relative;
}

// The simulated robot's localiser parameters (its laser mounting, its
// odometry's noise), for a localisation component that follows the simulator
// or a feeder made like it: without --params it would choose a real laser's
// preset from the first scan.
inline std::string SimulatedRobotParams() {
  return SourcePath("maps/params/office_sick.xml");
}

}  // namespace structloc::testing
