// Robot parameter file reading, writing and validation.
#include "robot_parameters.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "strict_xml.hpp"

namespace structloc::kinematics {
namespace {

std::string Text(double value) {
  std::ostringstream out;
  out << std::setprecision(6) << value;
  return out.str();
}

// Throws std::invalid_argument "robot: NAME = VALUE; must be RULE" unless `ok`.
void Require(bool ok, const char* name, double value, const std::string& rule) {
  if (!ok) {
    throw std::invalid_argument(std::string("robot: ") + name + " = " + Text(value) +
                                " is implausible; it must be " + rule);
  }
}

std::string Range(double low, double high, const char* unit) {
  return Text(low) + " .. " + Text(high) + unit;
}

}  // namespace

void RobotParameters::Validate() const {
  const std::string length_range = Range(kMinRobotLength_m, kMaxRobotLength_m, " m");
  Require(std::isfinite(wheel_radius) && wheel_radius >= kMinRobotLength_m &&
              wheel_radius <= kMaxRobotLength_m,
          "wheel_radius", wheel_radius, length_range);
  Require(std::isfinite(axle_distance) && axle_distance >= kMinRobotLength_m &&
              axle_distance <= kMaxRobotLength_m,
          "axle_distance", axle_distance, length_range);
  Require(std::isfinite(steering_offset) && std::abs(steering_offset) < geometry::kPi,
          "steering_offset", steering_offset, "within (-pi, pi) rad");
  Require(std::isfinite(traction_ticks_per_rev) && traction_ticks_per_rev >= kMinTicksPerRev &&
              traction_ticks_per_rev <= kMaxTicksPerRev,
          "traction_ticks_per_rev", traction_ticks_per_rev,
          Range(kMinTicksPerRev, kMaxTicksPerRev, " ticks per wheel revolution"));
  Require(traction_counter_bits >= kMinCounterBits && traction_counter_bits <= kMaxCounterBits,
          "traction_counter_bits", traction_counter_bits,
          std::to_string(kMinCounterBits) + " .. " + std::to_string(kMaxCounterBits));
  Require(std::isfinite(steering_rad_per_tick) &&
              std::abs(steering_rad_per_tick) >= kMinSteeringRadPerTick &&
              std::abs(steering_rad_per_tick) <= kMaxSteeringRadPerTick,
          "steering_rad_per_tick", steering_rad_per_tick,
          "non-zero with magnitude " +
              Range(kMinSteeringRadPerTick, kMaxSteeringRadPerTick, " rad per tick"));
  Require(std::isfinite(steering_zero_tick) && std::abs(steering_zero_tick) <= kMaxSteeringZeroTick,
          "steering_zero_tick", steering_zero_tick,
          "within +-" + Text(kMaxSteeringZeroTick) + " ticks");
  const std::string mount_range =
      "within +-" + Text(kMaxRobotLength_m) + " m of the reference point";
  Require(std::isfinite(sensor.x) && std::abs(sensor.x) <= kMaxRobotLength_m, "sensor_x", sensor.x,
          mount_range);
  Require(std::isfinite(sensor.y) && std::abs(sensor.y) <= kMaxRobotLength_m, "sensor_y", sensor.y,
          mount_range);
  Require(std::isfinite(sensor.theta) && std::abs(sensor.theta) <= geometry::kPi, "sensor_theta",
          sensor.theta, "within [-pi, pi] rad");
}

int64_t RobotParameters::TickDelta(uint64_t previous, uint64_t current) const {
  const uint64_t modulus = uint64_t{1} << traction_counter_bits;
  const uint64_t mask = modulus - 1;
  const uint64_t diff = (current - previous) & mask;
  // Differences above half the range are backwards motion across the wrap;
  // modulus - diff <= 2^62 always fits (2^63 itself, for 63 bits, would not).
  return diff >= modulus / 2 ? -static_cast<int64_t>(modulus - diff) : static_cast<int64_t>(diff);
}

uint64_t RobotParameters::MaxTractionTick() const {
  return (uint64_t{1} << traction_counter_bits) - 1;
}

RobotParameters LoadRobotParameters(const std::string& path) {
  const auto file = config::XmlFile::Load(path);
  const auto& root = file.Root("robot");
  if (root.FirstChildElement() != nullptr) file.Fail(root, "takes no child elements");
  config::AttributeReader a(file, root);
  RobotParameters p;
  p.wheel_radius = a.Double("wheel_radius");
  p.axle_distance = a.Double("axle_distance");
  p.steering_offset = a.Double("steering_offset");
  p.traction_ticks_per_rev = a.Double("traction_ticks_per_rev");
  // Range-checked as read, before narrowing to int (4294967328 must not become 32).
  const long long bits = a.Integer("traction_counter_bits");
  if (bits < kMinCounterBits || bits > kMaxCounterBits) {
    a.Fail("traction_counter_bits = " + std::to_string(bits) + " is implausible; it must be " +
           std::to_string(kMinCounterBits) + " .. " + std::to_string(kMaxCounterBits));
  }
  p.traction_counter_bits = static_cast<int>(bits);
  p.steering_rad_per_tick = a.Double("steering_rad_per_tick");
  p.steering_zero_tick = a.Double("steering_zero_tick");
  p.sensor.x = a.OptionalDouble("sensor_x").value_or(0.0);
  p.sensor.y = a.OptionalDouble("sensor_y").value_or(0.0);
  p.sensor.theta = a.OptionalDouble("sensor_theta").value_or(0.0);
  a.Finish();
  try {
    p.Validate();
  } catch (const std::invalid_argument& e) {
    file.Fail(root, e.what());
  }
  return p;
}

std::string XmlCommentBody(const std::string& text) {
  std::string body;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '-' && !body.empty() && body.back() == '-') body += ' ';
    body += byte < 0x20 || byte == 0x7f ? '?' : c;
  }
  if (!body.empty() && body.back() == '-') body += ' ';
  return body;
}

void WriteRobotParameters(const RobotParameters& p, std::ostream& out, const std::string& comment) {
  out << std::setprecision(10);
  out << "<?xml version=\"1.0\"?>\n<!-- " << XmlCommentBody(comment) << " -->\n"
      << "<robot wheel_radius=\"" << p.wheel_radius << "\" axle_distance=\"" << p.axle_distance
      << "\" steering_offset=\"" << p.steering_offset << "\"\n       traction_ticks_per_rev=\""
      << p.traction_ticks_per_rev << "\" traction_counter_bits=\"" << p.traction_counter_bits
      << "\" steering_rad_per_tick=\"" << p.steering_rad_per_tick << "\" steering_zero_tick=\""
      << p.steering_zero_tick << "\"\n       sensor_x=\"" << p.sensor.x << "\" sensor_y=\""
      << p.sensor.y << "\" sensor_theta=\"" << p.sensor.theta << "\"/>\n";
}

}  // namespace structloc::kinematics
