// The robot's odometry parameters (SI units, radians), as read from a robot
// parameter file shared by the simulator's odometry, the localisation and the
// calibration. Two kinds of drive:
//   <robot [kind="tricycle"] wheel_radius="0.185" axle_distance="0.62" steering_offset="0"
//          traction_ticks_per_rev="4096" traction_counter_bits="32"
//          steering_rad_per_tick="0.000767" steering_zero_tick="0"
//          [sensor_x="0" sensor_y="0" sensor_theta="0"]/>
//   <robot kind="differential" left_wheel_radius="0.1" right_wheel_radius="0.1"
//          wheel_separation="0.5" ticks_per_rev="4096" counter_bits="32"
//          [sensor_x="0" sensor_y="0" sensor_theta="0"]/>
// A file without `kind` is a tricycle. Tricycle: the reference point is the
// middle of the rear axle. steering angle =
// (steering_ticks - steering_zero_tick) * steering_rad_per_tick + steering_offset;
// traction wheel angle increment = (tick difference modulo 2^bits) * 2 pi /
// traction_ticks_per_rev; distance = wheel_radius * wheel angle (EQ 46).
// Differential drive: the reference point is the middle of the wheel axle;
// each wheel's counter increases when it rolls forward, wraps at 2^counter_bits
// and turns ticks_per_rev per revolution (the traction_* members hold them).
// sensor_* is the pose on the robot of the sensor whose position fixes the
// calibration uses (default: the reference point itself).
// Values outside the plausibility bounds below are refused: they are typing or
// unit mistakes (millimetres for metres, degrees for radians, 1e-300 ticks).
// Every key is declared once, in RobotParameterTable() (key, range, unit,
// description; the struct members hold the defaults); loading, validation,
// writing and the `structloc params --robot` listing derive from it.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include "structloc/config/option_table.hpp"
#include "structloc/geometry/pose2d.hpp"

namespace structloc::kinematics {

// Plausibility bounds every robot file must meet (see RobotParameters::Validate).
inline constexpr double kMinRobotLength_m = 1e-3;   // wheel radius, axle distance
inline constexpr double kMaxRobotLength_m = 100.0;  // ... and |sensor_x|, |sensor_y|
inline constexpr double kMinTicksPerRev = 1.0;      // traction_ticks_per_rev
inline constexpr double kMaxTicksPerRev = 1e9;
inline constexpr double kMinSteeringRadPerTick = 1e-9;  // |steering_rad_per_tick|
inline constexpr double kMaxSteeringRadPerTick = 1.0;
inline constexpr double kMaxSteeringZeroTick = 1e15;  // |steering_zero_tick|, exact in double
inline constexpr int kMinCounterBits = 8;             // traction_counter_bits
inline constexpr int kMaxCounterBits = 63;

enum class DriveKind { kTricycle, kDifferential };

struct RobotParameters {
  DriveKind kind = DriveKind::kTricycle;
  double wheel_radius = 0.185;   // m, traction (front) wheel
  double axle_distance = 0.62;   // m, front wheel axis to rear axle
  double steering_offset = 0.0;  // rad
  double traction_ticks_per_rev = 4096;
  int traction_counter_bits = 32;  // counter wraps at 2^bits
  double steering_rad_per_tick = 0.000767;
  double steering_zero_tick = 0;
  geometry::Pose2D sensor;          // fix sensor on the robot
  double left_wheel_radius = 0.1;   // m, differential drive only
  double right_wheel_radius = 0.1;  // m
  double wheel_separation = 0.5;    // m, between the wheels' contact points

  // Throws std::invalid_argument naming the broken parameter.
  void Validate() const;

  // Decoding raw encoder readings.
  double SteeringAngle(double steering_ticks) const {
    return (steering_ticks - steering_zero_tick) * steering_rad_per_tick + steering_offset;
  }
  // Signed tick difference from `previous` to `current` across a counter wrap.
  int64_t TickDelta(uint64_t previous, uint64_t current) const;
  // Largest raw traction counter value, 2^traction_counter_bits - 1.
  uint64_t MaxTractionTick() const;
  double WheelAngle(int64_t tick_delta) const {
    return static_cast<double>(tick_delta) * 2.0 * geometry::kPi / traction_ticks_per_rev;
  }
};

// The one declaration of the <robot> element's keys of each kind. Out-of-range values read
// "robot: KEY = VALUE is implausible; it must be ...".
config::OptionTable<RobotParameters> RobotParameterTable(DriveKind kind = DriveKind::kTricycle);
// Lists every key: default, unit, valid values, meaning.
void PrintRobotParameters(std::ostream& out);

// Throws config::ConfigError "FILE:LINE: problem" for a missing, malformed or
// implausible parameter.
RobotParameters LoadRobotParameters(const std::string& path);
// Writes a parameter file (the calibration's output) to `out`; `comment` may
// hold any text (paths with "--" included): it is made safe for an XML comment.
void WriteRobotParameters(const RobotParameters& p, std::ostream& out, const std::string& comment);
// `text` as the body of a well-formed XML comment: no "--", no trailing "-",
// control characters replaced by '?'.
std::string XmlCommentBody(const std::string& text);

}  // namespace structloc::kinematics
