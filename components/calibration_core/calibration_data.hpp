// The calibration's input files: encoders.csv ("t,traction_ticks,steering_ticks")
// and fixes.csv ("t,x,y,theta[,var_x,var_y,var_theta]"), with every problem
// (empty file, wrong header, unsorted or duplicate times, non-numeric values)
// a clear error naming file and line. A fix with NaN is dropped and counted.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "pose2d.hpp"

namespace structloc::calibration {

struct EncoderSample {
  double t = 0.0;
  uint64_t traction_ticks = 0;  // raw counter (may wrap)
  double steering_ticks = 0.0;  // raw absolute steering encoder
};

struct Fix {
  double t = 0.0;
  geometry::Pose2D pose;  // map frame, of the robot or of its fix sensor
  bool has_variance = false;
  Eigen::Vector3d variance{0, 0, 0};
};

struct FixesFile {
  std::vector<Fix> fixes;
  size_t dropped_non_finite = 0;
};

// Throw std::runtime_error with "FILE:LINE: problem".
std::vector<EncoderSample> ReadEncodersCsv(const std::string& path);
FixesFile ReadFixesCsv(const std::string& path);

}  // namespace structloc::calibration
