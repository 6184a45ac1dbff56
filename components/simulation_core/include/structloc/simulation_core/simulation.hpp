// The simulated robot and laser, stepped every `step_s` (10 ms, EQ 48): the
// true tricycle moves with its true parameters and wheel slip; encoders count
// as a real robot's do (quantised, wrapping traction counter, absolute
// steering encoder); odometry is dead reckoning from those encoders with the
// nominal parameters; the laser takes every beam at its own time while the
// robot moves, with the sensor faults of the thesis' Fig. 8. Deterministic:
// the same scenario and seed give bit-for-bit the same output. DDS-free.
#pragma once

#include <deque>
#include <optional>
#include <random>
#include <vector>

#include "structloc/kinematics/tricycle.hpp"
#include "structloc/simulation_core/scenario.hpp"

namespace structloc::simulation_core {

// One laser scan, with LaserScan's conventions (beam i at angle_min + i *
// angle_increment, taken at stamp + i * time_increment).
struct SimScan {
  double stamp = 0.0;
  double angle_min = 0.0, angle_increment = 0.0, time_increment = 0.0, scan_time = 0.0;
  double range_min = 0.0, range_max = 0.0;
  std::vector<float> ranges;
  // The robot base in the map frame when the first beam was taken (at
  // `stamp`, less the laser's stamp_latency_s) ...
  geometry::Pose2D truth;
  geometry::Pose2D odometry;  // ... and in the odom frame at `stamp`
};

// The state after one integration step.
struct SimState {
  double time = 0.0;
  geometry::Pose2D truth;       // map frame
  geometry::Pose2D odometry;    // odom frame (starts at the origin)
  double odom_linear = 0.0;     // m/s, from the encoders and nominal parameters
  double odom_angular = 0.0;    // rad/s
  uint64_t traction_ticks = 0;  // raw counter, wrapped at 2^bits
  int64_t steering_ticks = 0;
  uint64_t left_ticks = 0;  // differential drive: raw wheel counters, wrapped at 2^bits
  uint64_t right_ticks = 0;
  double steering_true_rad = 0.0;
};

class Simulation {
 public:
  explicit Simulation(const Scenario& scenario);

  // Advances one step; returns the new state.
  const SimState& Step();
  const SimState& State() const { return state_; }
  // A scan whose last beam was taken during the last step, if any (with a
  // stamp latency: whose stamp fell in the last step).
  std::optional<SimScan> TakeScan();
  bool Finished() const;
  // Velocity command for PathSpec::Mode::kCmdVel (m/s, rad/s).
  void CommandVelocity(double linear, double angular);
  // Positions of the people now (for rendering and tests).
  std::vector<world_model::Circle> People() const;
  const Scenario& GetScenario() const { return scenario_; }
  double LaserTimeIncrement() const { return scan_.time_increment; }

 private:
  void Control(double* wheel_rate, double* steering);
  // A differential drive's step: the tricycle control law's motion driven by
  // two wheels (nominal parameters command them, the true ones move the robot).
  void StepDifferential(double wheel_angle, double steering, double slip_factor);
  void MovePeople(double t);
  void CastBeams(const geometry::Pose2D& from, const geometry::Pose2D& to, double t0, double t1);
  // Gives out the scans stamped late whose stamps fell by t1 (a stamp
  // within a scan's sweep: when it is complete), with the odometry at their
  // stamps.
  void ReleaseStampedLate(double t0, double t1);
  float Measure(const world_model::Scene& scene, const geometry::Pose2D& laser_pose, int beam);

  Scenario scenario_;
  kinematics::RobotParameters true_params_;
  SimState state_;
  kinematics::DeadReckoning dead_reckoning_;
  double wheel_ticks_ = 0.0;                                 // continuous traction counter
  double left_wheel_ticks_ = 0.0, right_wheel_ticks_ = 0.0;  // differential drive
  world_model::Scene scene_;   // world + obstacles, then the people at the last step
  size_t static_circles_ = 0;  // circles in scene_ that never move
  std::mt19937 motion_rng_;
  std::mt19937 laser_rng_;
  size_t waypoint_ = 0;                  // the waypoint the robot heads for
  size_t next_teleport_ = 0;             // the scenario's next teleport
  Eigen::Vector2d segment_start_{0, 0};  // where the current path segment starts
  double dwell_until_ = -1.0;
  bool path_done_ = false;
  double cmd_linear_ = 0.0, cmd_angular_ = 0.0;
  // Scan in progress.
  SimScan scan_;
  int next_beam_ = 0;
  int scan_index_ = 0;
  double previous_true_range_ = 0.0;
  std::optional<SimScan> completed_;
  std::deque<SimScan> stamped_late_;  // complete, waiting for their late stamps
  // (time, odometry) back to the oldest stamp a complete scan can have.
  std::deque<std::pair<double, geometry::Pose2D>> odometry_history_;
  double last_step_time_ = 0.0;
  geometry::Pose2D last_truth_, last_odometry_;
};

}  // namespace structloc::simulation_core
