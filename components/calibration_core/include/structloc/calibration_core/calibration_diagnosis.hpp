// Why a calibration failed, in terms a user can act on: looks at the raw
// inputs for the usual mistakes (an encoder that never changes, a traction
// counter that wraps earlier than traction_counter_bits says, odometry
// distances far from the fixes' because ticks per revolution or the wheel
// radius are wrong, fixes that hardly move). DDS-free.
#pragma once

#include <string>
#include <vector>

#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/kinematics/robot_parameters.hpp"

namespace structloc::calibration_core {

// Thresholds of the diagnosis, with their defaults.
struct DiagnosisLimits {
  double min_fix_travel_m = 1.0;    // fixes travelling less say nothing about distances
  double anchor_step_m = 0.2;       // fix path measured between points this far apart (noise)
  double max_distance_ratio = 2.0;  // odometry vs fix distance beyond this (or 1/this) is wrong
  double min_fix_turn_rad = 3.14;   // fixes turning this much need a moving steering encoder
};

// Likely causes, most specific first; empty when none of the checks fires.
std::vector<std::string> LikelyCauses(const std::vector<EncoderSample>& encoders,
                                      const std::vector<Fix>& fixes,
                                      const kinematics::RobotParameters& nominal,
                                      const DiagnosisLimits& limits = {});

}  // namespace structloc::calibration_core
