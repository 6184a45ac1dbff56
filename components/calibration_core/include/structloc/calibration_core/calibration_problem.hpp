// The odometry calibration's least-squares problem (thesis 6.5.4): the
// encoder motion between pairs of position fixes far enough apart, and the
// whitened residuals between each measured relative sensor motion and the
// one dead reckoning (EQ 46-48) predicts for candidate parameters. DDS-free.
#pragma once

#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc/geometry/pose2d.hpp"
#include "structloc/kinematics/robot_parameters.hpp"

namespace structloc::calibration_core {

// One value per calibration parameter, indexed by Parameter.
using ParameterValues = std::array<double, kParameterCount>;
// One flag per calibration parameter, indexed by Parameter.
using ParameterMask = std::array<bool, kParameterCount>;

// `base` with the calibration parameters replaced by `values`.
kinematics::RobotParameters WithValues(const kinematics::RobotParameters& base,
                                       const ParameterValues& values);
// The calibration parameters of `p`.
ParameterValues ValuesOf(const kinematics::RobotParameters& p);

class CalibrationProblem {
 public:
  // Pairs consecutive fixes at least options.min_fix_travel_m or
  // min_fix_turn_rad apart; intervals outside the encoder recording or across
  // an encoder gap are skipped (and counted).
  CalibrationProblem(const std::vector<EncoderSample>& encoders, const std::vector<Fix>& fixes,
                     const kinematics::RobotParameters& nominal, const CalibrationOptions& options);

  size_t Size() const { return intervals_.size(); }
  size_t EncoderGaps() const { return encoder_gaps_; }
  size_t IntervalsSkipped() const { return intervals_skipped_; }

  // Whitened residuals (3 per interval: x, y, theta) for the full parameter set.
  Eigen::VectorXd Whitened(const ParameterValues& values) const;

 private:
  // The encoder motion between two fixes: tick increments (unwrapped, possibly
  // fractional at the ends) and the steering reading that applies to each.
  struct Interval {
    std::vector<std::pair<double, double>> steps;  // (tick delta, steering ticks)
    geometry::Pose2D measured;                     // fix i -> fix j, in fix i's frame
    Eigen::Matrix3d information;                   // inverse covariance of `measured`
  };

  Eigen::Vector3d DefaultVariance() const;
  Eigen::Matrix3d RelativeInformation(const Fix& from, const Fix& to) const;

  kinematics::RobotParameters nominal_;
  CalibrationOptions options_;
  std::vector<Interval> intervals_;
  size_t encoder_gaps_ = 0;
  size_t intervals_skipped_ = 0;
};

}  // namespace structloc::calibration_core
