// The odometry calibration's batch least-squares problem (thesis 6.5.4, with
// every fix and every baseline used): the unknowns are the robot's pose at
// each fix time and the calibration parameters. Each fix measures its pose
// (with the fix covariance); the encoder motion between consecutive fix times,
// re-run by dead reckoning (EQ 46-48) for candidate parameters, constrains
// neighbouring poses with a process noise (wheel slip, heading noise,
// quantisation) that grows with the distance driven. The chain of motion
// constraints carries the long baselines: the wheel radius shows in the
// distance between fixes far apart while each fix's noise stays its own.
// Residuals and the sparse Jacobian are whitened. DDS-free.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
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

// A point of the problem: the robot's base pose at every fix and the parameters.
struct CalibrationState {
  std::vector<geometry::Pose2D> poses;
  ParameterValues values{};
};

// The full problem, or the coarse one that gives the full one its start.
enum class ProblemScope {
  kEveryFix,
  // Fixes at least min_fix_travel_m or min_fix_turn_rad apart, each link's
  // noise including both fixes' (for a solve with the poses held at the
  // fixes: the relative motion between fixes, thesis 6.5.4, robust to a
  // nominal far from the truth).
  kRelativeMotion,
};

class CalibrationProblem {
 public:
  // Keeps the fixes inside the encoder recording; consecutive fixes are
  // linked by their encoder motion unless an encoder gap lies between them
  // (counted). The process noise is propagated with the nominal parameters.
  CalibrationProblem(const std::vector<EncoderSample>& encoders, const std::vector<Fix>& fixes,
                     const kinematics::RobotParameters& nominal, const CalibrationOptions& options,
                     ProblemScope scope = ProblemScope::kEveryFix);

  size_t FixCount() const { return fixes_.size(); }
  // Motion constraints between consecutive fixes.
  size_t Size() const { return links_.size(); }
  size_t EncoderGaps() const { return encoder_gaps_; }
  // Pairs of consecutive fixes left unlinked (an encoder gap between them).
  size_t IntervalsSkipped() const { return intervals_skipped_; }
  const std::vector<Fix>& Fixes() const { return fixes_; }

  // Poses straight from the fixes (through the sensor mounting), nominal parameters.
  CalibrationState Initial() const;
  // Poses straight from the fixes through the mounting of `values`, and `values`.
  CalibrationState AtFixes(const ParameterValues& values) const;
  // Whitened residuals: 3 per fix (x, y, theta), then 3 per motion constraint.
  Eigen::VectorXd Whitened(const CalibrationState& state) const;
  // Jacobian of Whitened with respect to the poses (3 columns per fix, in
  // order) followed by the parameters listed in `active`.
  Eigen::SparseMatrix<double> Jacobian(const CalibrationState& state,
                                       const std::vector<size_t>& active) const;
  // `state` moved by `delta` (ordered as the Jacobian's columns).
  CalibrationState Moved(const CalibrationState& state, const Eigen::VectorXd& delta,
                         const std::vector<size_t>& active) const;

 private:
  // Encoder motion between fix `from` and fix `from + 1`: tick increments
  // (unwrapped, fractional at the ends) with the steering reading of each.
  struct Link {
    size_t from = 0;
    std::vector<std::pair<double, double>> steps;
    Eigen::Matrix3d whitening;  // upper Cholesky factor of the inverse process covariance
  };

  // Relative base motion over a link for parameters `p`, with its process
  // covariance when `covariance` is not null.
  geometry::Pose2D Predict(const Link& link, const kinematics::RobotParameters& p,
                           Eigen::Matrix3d* covariance) const;
  Eigen::Vector3d FixVariance(const Fix& fix) const;

  kinematics::RobotParameters nominal_;
  CalibrationOptions options_;
  std::vector<Fix> fixes_;
  std::vector<Eigen::Matrix3d> fix_whitening_;
  std::vector<Link> links_;
  size_t encoder_gaps_ = 0;
  size_t intervals_skipped_ = 0;
};

}  // namespace structloc::calibration_core
