// The thesis' tricycle (thesis 5.2, EQ 46-48): one front wheel, driven and
// steered, two passive rear wheels; the reference point is the middle of the
// rear axle. Also the differential drive of most indoor robots (two driven
// wheels on one axle, the reference point in its middle), integrated along
// the same arcs. Used for the simulator's true motion, for dead reckoning from
// encoders (odometry), and by the calibration to re-run recorded encoders.
#pragma once

#include <cstdint>
#include <optional>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/kinematics/robot_parameters.hpp"

namespace structloc::kinematics {

// One integration step (EQ 48): the traction wheel turned by `wheel_angle`
// (rad) while steered at `steering` (rad). Exact arc for constant steering.
geometry::Pose2D Advance(const geometry::Pose2D& pose, double wheel_angle, double steering,
                         double wheel_radius, double axle_distance);

// One integration step along a circular arc: the reference point travels
// `distance` while the heading changes by `dtheta` (EQ 47 with constant v
// and omega, exact).
geometry::Pose2D AdvanceArc(const geometry::Pose2D& pose, double distance, double dtheta);

// One step of a differential drive: the left and right wheels rolled
// `left_m` and `right_m` (negative backwards), `separation` apart.
geometry::Pose2D AdvanceDifferential(const geometry::Pose2D& pose, double left_m, double right_m,
                                     double separation);

// Dead reckoning from raw encoder readings with a set of parameters.
class DeadReckoning {
 public:
  explicit DeadReckoning(const RobotParameters& parameters, const geometry::Pose2D& start = {});
  // Feeds one encoder sample; the first only sets the reference counter. The
  // steering angle reported with a sample applies to the wheel motion that
  // ended at it (the convention of the simulator and of our recordings).
  void Add(uint64_t traction_ticks, double steering_ticks);
  // A differential drive's sample: both raw wheel counters (the first sets the reference).
  void AddWheels(uint64_t left_ticks, uint64_t right_ticks);
  const geometry::Pose2D& Pose() const { return pose_; }
  double Distance() const { return distance_; }

 private:
  RobotParameters parameters_;
  geometry::Pose2D pose_;
  std::optional<uint64_t> last_ticks_;
  uint64_t last_right_ticks_ = 0;
  double distance_ = 0.0;
};

}  // namespace structloc::kinematics
