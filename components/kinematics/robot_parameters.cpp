// Robot parameter file reading, writing and validation.
#include "robot_parameters.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "strict_xml.hpp"

namespace structloc::kinematics {

void RobotParameters::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("robot: ") + what);
  };
  require(std::isfinite(wheel_radius) && wheel_radius > 0, "wheel_radius must be > 0");
  require(std::isfinite(axle_distance) && axle_distance > 0, "axle_distance must be > 0");
  require(std::isfinite(steering_offset) && std::abs(steering_offset) < geometry::kPi,
          "steering_offset must be within (-pi, pi)");
  require(std::isfinite(traction_ticks_per_rev) && traction_ticks_per_rev > 0,
          "traction_ticks_per_rev must be > 0");
  require(traction_counter_bits >= 8 && traction_counter_bits <= 63,
          "traction_counter_bits must be 8..63");
  require(std::isfinite(steering_rad_per_tick) && steering_rad_per_tick != 0,
          "steering_rad_per_tick must be non-zero");
  require(std::isfinite(steering_zero_tick), "steering_zero_tick must be finite");
  require(geometry::IsFinite(sensor), "sensor_x/y/theta must be finite");
}

int64_t RobotParameters::TickDelta(uint64_t previous, uint64_t current) const {
  const uint64_t modulus = uint64_t{1} << traction_counter_bits;
  const uint64_t mask = modulus - 1;
  const uint64_t diff = (current - previous) & mask;
  // Differences above half the range are backwards motion across the wrap.
  return diff >= modulus / 2 ? static_cast<int64_t>(diff) - static_cast<int64_t>(modulus)
                             : static_cast<int64_t>(diff);
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
  p.traction_counter_bits = static_cast<int>(a.Integer("traction_counter_bits"));
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

void SaveRobotParameters(const RobotParameters& p, const std::string& path,
                         const std::string& comment) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << std::setprecision(10);
  out << "<?xml version=\"1.0\"?>\n<!-- " << comment << " -->\n"
      << "<robot wheel_radius=\"" << p.wheel_radius << "\" axle_distance=\"" << p.axle_distance
      << "\" steering_offset=\"" << p.steering_offset << "\"\n       traction_ticks_per_rev=\""
      << p.traction_ticks_per_rev << "\" traction_counter_bits=\"" << p.traction_counter_bits
      << "\" steering_rad_per_tick=\"" << p.steering_rad_per_tick << "\" steering_zero_tick=\""
      << p.steering_zero_tick << "\"\n       sensor_x=\"" << p.sensor.x << "\" sensor_y=\""
      << p.sensor.y << "\" sensor_theta=\"" << p.sensor.theta << "\"/>\n";
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace structloc::kinematics
