// The calibration's input files: encoders.csv ("t,traction_ticks,steering_ticks"
// for a tricycle, "t,left_ticks,right_ticks" for a differential drive) and fixes.csv
// ("t,x,y,theta[,var_x,var_y,var_theta]"), with every problem (empty file, wrong header, unsorted
// or duplicate times, non-numeric values, traction ticks that are not integers of the robot's
// counter width) a clear error naming file and line. A UTF-8 byte-order mark before the header is
// accepted. A fix with NaN, an infinite value or a negative variance is
// dropped and counted by reason.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/kinematics/robot_parameters.hpp"

namespace structloc::calibration_core {

struct EncoderSample {
  double t = 0.0;
  uint64_t traction_ticks = 0;  // tricycle: raw counter (may wrap)
  double steering_ticks = 0.0;  // tricycle: raw absolute steering encoder
  uint64_t left_ticks = 0;      // differential drive: raw wheel counters (may wrap)
  uint64_t right_ticks = 0;
};

struct Fix {
  double t = 0.0;
  geometry::Pose2D pose;  // map frame, of the robot or of its fix sensor
  bool has_variance = false;
  Eigen::Vector3d variance{0, 0, 0};
};

struct FixesFile {
  std::vector<Fix> fixes;
  size_t dropped_non_finite = 0;         // NaN or infinite pose or variance...
  size_t dropped_infinite = 0;           // ... of which infinite (and no NaN)
  size_t dropped_negative_variance = 0;  // finite, but a variance below 0
  size_t first_dropped_line = 0;         // 0 when none was dropped
};

// "none dropped", or "3 dropped (1 with NaN, 1 with an infinite value, 1 with
// a negative variance; first at line 7)".
std::string DescribeDropped(const FixesFile& file);

// Throw std::runtime_error with "FILE:LINE: problem". Wheel counters must be
// decimal integers no larger than 2^counter_bits - 1 (the robot file's
// counter width; 64 accepts any unsigned 64-bit value); the header must be the
// one of the robot's drive kind.
std::vector<EncoderSample> ReadEncodersCsv(
    const std::string& path, int traction_counter_bits = 64,
    kinematics::DriveKind kind = kinematics::DriveKind::kTricycle);
FixesFile ReadFixesCsv(const std::string& path);

}  // namespace structloc::calibration_core
