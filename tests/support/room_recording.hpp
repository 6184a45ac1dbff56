// The robustness room scenario recorded once per test process (24 scans:
// run.clf, truth.tum, initial_pose, encoders.csv), for tests that run the
// CLI on a small real-looking recording, or write hostile variants of it.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "structloc/simulation_core/recorder.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc::testing {

inline const TempDir& RoomRecording() {
  static const TempDir dir;
  static const bool recorded = [] {
    simulation_core::RecordScenario(
        simulation_core::LoadScenario(SourcePath("maps/scenarios/robustness_room.xml")),
        dir.Path());
    return true;
  }();
  EXPECT_TRUE(recorded);
  return dir;
}

inline std::string RoomLog() {
  return RoomRecording() / "run.clf";
}

inline std::string RoomTruth() {
  return RoomRecording() / "truth.tum";
}

// One ROBOTLASER1 line of five beams of 1 m from the origin, every field
// finite; a `resolution` of 1e308 puts the later beams' angles at infinity.
inline std::string FiveBeamLaserLine(const std::string& resolution, const std::string& stamp) {
  return "ROBOTLASER1 0 -1.5707963 3.14159 " + resolution +
         " 20 0.01 0 5 1.0 1.0 1.0 1.0 1.0 0 0 0 0 0 0 0 0 0 0 0 0 " + stamp + " host " + stamp +
         "\n";
}

}  // namespace structloc::testing
