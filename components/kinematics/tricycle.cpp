// Tricycle kinematics and dead reckoning (see header).
#include "structloc/kinematics/tricycle.hpp"

#include <cmath>

namespace structloc::kinematics {

geometry::Pose2D Advance(const geometry::Pose2D& pose, double wheel_angle, double steering,
                         double wheel_radius, double axle_distance) {
  const double s = wheel_angle * wheel_radius;  // front wheel path length
  const double ds = s * std::cos(steering);     // reference point travel (EQ 46)
  const double dtheta = s * std::sin(steering) / axle_distance;
  return AdvanceArc(pose, ds, dtheta);
}

geometry::Pose2D AdvanceArc(const geometry::Pose2D& pose, double ds, double dtheta) {
  double fx, fy;
  if (std::abs(dtheta) < 1e-9) {
    fx = ds * (1.0 - dtheta * dtheta / 6.0);
    fy = ds * dtheta / 2.0;
  } else {
    fx = ds * std::sin(dtheta) / dtheta;
    fy = ds * (1.0 - std::cos(dtheta)) / dtheta;
  }
  const double c = std::cos(pose.theta), sn = std::sin(pose.theta);
  return {pose.x + c * fx - sn * fy, pose.y + sn * fx + c * fy,
          geometry::WrapAngle(pose.theta + dtheta)};
}

geometry::Pose2D AdvanceDifferential(const geometry::Pose2D& pose, double left_m, double right_m,
                                     double separation) {
  return AdvanceArc(pose, 0.5 * (left_m + right_m), (right_m - left_m) / separation);
}

DeadReckoning::DeadReckoning(const RobotParameters& parameters, const geometry::Pose2D& start)
    : parameters_(parameters), pose_(start) {}

void DeadReckoning::Add(uint64_t traction_ticks, double steering_ticks) {
  const double steering = parameters_.SteeringAngle(steering_ticks);
  if (last_ticks_) {
    const double wheel =
        parameters_.WheelAngle(parameters_.TickDelta(*last_ticks_, traction_ticks));
    pose_ = Advance(pose_, wheel, steering, parameters_.wheel_radius, parameters_.axle_distance);
    distance_ += std::abs(wheel * parameters_.wheel_radius);
  }
  last_ticks_ = traction_ticks;
}

void DeadReckoning::AddWheels(uint64_t left_ticks, uint64_t right_ticks) {
  if (last_ticks_) {
    const double left = parameters_.WheelAngle(parameters_.TickDelta(*last_ticks_, left_ticks)) *
                        parameters_.left_wheel_radius;
    const double right =
        parameters_.WheelAngle(parameters_.TickDelta(last_right_ticks_, right_ticks)) *
        parameters_.right_wheel_radius;
    pose_ = AdvanceDifferential(pose_, left, right, parameters_.wheel_separation);
    distance_ += std::abs(0.5 * (left + right));
  }
  last_ticks_ = left_ticks;
  last_right_ticks_ = right_ticks;
}

}  // namespace structloc::kinematics
