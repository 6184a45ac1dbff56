// A simulation scenario: the world model, unmodelled obstacles and people, the
// robot's nominal parameters and how the true robot differs from them, the
// laser and its faults, the path, the duration and the seed. Read from XML
// (maps/scenarios/*.xml); every problem names file, line and attribute.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "structloc/kinematics/robot_parameters.hpp"
#include "structloc/world_model/ray_cast.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::simulation_core {

// How the real robot differs from its nominal parameters.
struct TrueRobotErrors {
  double wheel_radius_scale = 1.0;  // true radius = nominal * scale
  double axle_distance_scale = 1.0;
  double steering_offset_rad = 0.0;  // added to the nominal steering offset
  double wheel_slip_std = 0.0;       // relative, per 10 ms step
  int64_t traction_start_tick = 0;   // initial counter value (test wrap-around)
  // Differential drive: true left / right radius and separation = nominal * scale.
  double left_wheel_radius_scale = 1.0;
  double right_wheel_radius_scale = 1.0;
  double wheel_separation_scale = 1.0;
};

struct LaserSpec {
  geometry::Pose2D mount;  // on the robot (base_link -> laser)
  double field_of_view_rad = 2 * geometry::kPi;
  int beams = 300;
  double rate_hz = 10.0;  // revolutions per second
  double min_range_m = 0.05;
  double max_range_m = 30.0;
  double noise_std_m = 0.0;              // Gaussian range noise
  double resolution_m = 0.0;             // range quantisation (SICK: 0.05), 0 = none
  bool no_return_is_max = false;         // "no return" as max_range_m + 1 instead of +inf
  double spurious_probability = 0.0;     // short random returns
  double mixed_pixel_probability = 0.0;  // at depth jumps > 0.2 m
  // Each scan stamped, and given out, this long after its first beam was
  // taken: a laser stamped when its readings arrive (a slow serial line).
  double stamp_latency_s = 0.0;
  std::vector<std::pair<double, double>> blocked_sectors;  // [from, to] rad, laser frame
};

struct PathSpec {
  enum class Mode { kWaypoints, kStopLookMove, kCmdVel };
  Mode mode = Mode::kWaypoints;
  double speed_m_s = 0.5;
  double dwell_s = 0.0;      // stop-look-move: standing time at each waypoint
  double lookahead_m = 0.6;  // pure-pursuit look-ahead
  bool loop = false;
  std::vector<Eigen::Vector2d> waypoints;
};

// The robot carried elsewhere at `at_s` (kidnapped: its encoders, and so its
// odometry, see nothing), then heading for waypoint `next_waypoint`.
struct Teleport {
  double at_s = 0.0;
  geometry::Pose2D pose;  // robot base, map frame
  size_t next_waypoint = 0;
};

struct Person {
  double radius_m = 0.25;
  double speed_m_s = 1.0;
  std::vector<Eigen::Vector2d> waypoints;  // walked in a loop
};

struct Scenario {
  std::string name;
  uint32_t seed = 1;
  double duration_s = 60.0;
  double step_s = 0.01;        // integration step (EQ 48)
  double odom_rate_hz = 50.0;  // odometry and encoder publication rate
  std::shared_ptr<const world_model::WorldModel> world;
  std::string world_path;
  kinematics::RobotParameters nominal;
  std::string robot_path;
  TrueRobotErrors errors;
  geometry::Pose2D initial_pose;  // robot base, map frame
  LaserSpec laser;
  PathSpec path;
  world_model::Scene obstacles;  // static, unmodelled
  std::vector<Person> people;
  std::vector<Teleport> teleports;  // in time order

  kinematics::RobotParameters TrueParameters() const;
};

// Bounds on what one scenario may ask of the simulator, so that a typo such as
// rate_hz="1e9" or duration_s="1e9" is refused with file:line instead of
// hanging or filling the disk. Geometry is bounded by `world` (WorldLimits).
struct ScenarioLimits {
  static constexpr double kDefaultMaxDurationS = 3600.0;

  double max_duration_s = kDefaultMaxDurationS;  // simulated seconds
  double min_step_s = 1e-4;                      // integration step 0.1 ms ..
  double max_step_s = 0.1;                       // .. 100 ms
  double min_rate_hz = 0.1;                      // laser revolutions and odometry rate
  double max_laser_rate_hz = 100.0;
  double max_odom_rate_hz = 1000.0;
  int min_beams = 10;
  int max_beams = 100000;
  world_model::WorldLimits world;
};

Scenario LoadScenario(const std::string& path, const ScenarioLimits& limits = {});

}  // namespace structloc::simulation_core
