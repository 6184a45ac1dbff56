// Scenario XML reader (see scenario.hpp; schema in maps/scenarios/README.md).
#include <algorithm>
#include <filesystem>

#include "scenario.hpp"
#include "strict_xml.hpp"
#include "world_model_xml.hpp"

namespace structloc::simulation {
namespace {

using config::AttributeReader;
using config::XmlFile;

// A map-frame coordinate within the world limits (the message names the bound).
double Coordinate(AttributeReader& a, const char* name, const world::WorldLimits& limits) {
  return a.DoubleIn(name, -limits.max_abs_coordinate_m, limits.max_abs_coordinate_m);
}

// A size or radius in (0, limit].
double Size(AttributeReader& a, const char* name, double limit) {
  const double value = a.DoubleIn(name, 0.0, limit);
  if (!(value > 0.0)) a.Fail(std::string("attribute ") + name + " must be > 0");
  return value;
}

std::vector<Eigen::Vector2d> ReadWaypoints(const XmlFile& file, const tinyxml2::XMLElement& parent,
                                           const world::WorldLimits& limits) {
  config::RequireChildNames(file, parent, {"waypoint"});
  std::vector<Eigen::Vector2d> points;
  for (const auto* w = parent.FirstChildElement(); w != nullptr; w = w->NextSiblingElement()) {
    AttributeReader a(file, *w);
    points.emplace_back(Coordinate(a, "x", limits), Coordinate(a, "y", limits));
    a.Finish();
  }
  return points;
}

const tinyxml2::XMLElement& Required(const XmlFile& file, const tinyxml2::XMLElement& root,
                                     const char* name) {
  const auto* e = root.FirstChildElement(name);
  if (e == nullptr) file.Fail(root, std::string("missing <") + name + ">");
  if (e->NextSiblingElement(name) != nullptr)
    file.Fail(*e, std::string("more than one <") + name + ">");
  return *e;
}

std::string Resolve(const std::string& scenario_path, const std::string& relative) {
  if (!relative.empty() && relative[0] == '/') return relative;
  return (std::filesystem::path(scenario_path).parent_path() / relative)
      .lexically_normal()
      .string();
}

}  // namespace

kinematics::RobotParameters Scenario::TrueParameters() const {
  kinematics::RobotParameters p = nominal;
  p.wheel_radius *= errors.wheel_radius_scale;
  p.axle_distance *= errors.axle_distance_scale;
  p.steering_offset += errors.steering_offset_rad;
  return p;
}

Scenario LoadScenario(const std::string& path, const ScenarioLimits& limits) {
  const auto& geometry_limits = limits.world;
  const auto file = XmlFile::Load(path);
  const auto& root = file.Root("scenario");
  config::RequireChildNames(
      file, root, {"world", "robot", "true_robot", "initial_pose", "laser", "path", "obstacles"});
  Scenario s;
  {
    AttributeReader a(file, root);
    s.name = a.String("name");
    s.seed = a.IntegerIn<uint32_t>("seed");
    s.duration_s = Size(a, "duration_s", limits.max_duration_s);
    s.step_s = a.DoubleIn("step_s", limits.min_step_s, limits.max_step_s);
    s.odom_rate_hz = a.DoubleIn("odom_rate_hz", limits.min_rate_hz, limits.max_odom_rate_hz);
    a.Finish();
  }
  {
    const auto& e = Required(file, root, "world");
    AttributeReader a(file, e);
    s.world_path = Resolve(path, a.String("file"));
    a.Finish();
    s.world =
        std::make_shared<world::WorldModel>(world::LoadWorldModel(s.world_path, geometry_limits));
  }
  {
    const auto& e = Required(file, root, "robot");
    AttributeReader a(file, e);
    s.robot_path = Resolve(path, a.String("file"));
    a.Finish();
    s.nominal = kinematics::LoadRobotParameters(s.robot_path);
  }
  {
    const auto& e = Required(file, root, "true_robot");
    AttributeReader a(file, e);
    s.errors.wheel_radius_scale = a.PositiveDouble("wheel_radius_scale");
    s.errors.axle_distance_scale = a.PositiveDouble("axle_distance_scale");
    s.errors.steering_offset_rad = a.Double("steering_offset_rad");
    s.errors.wheel_slip_std = a.NonNegativeDouble("wheel_slip_std");
    // The simulated counter runs in double precision: exact up to 2^52 ticks.
    const int bits = std::min(s.nominal.traction_counter_bits, 52);
    s.errors.traction_start_tick =
        a.IntegerIn<int64_t>("traction_start_tick", 0, (int64_t{1} << bits) - 1);
    a.Finish();
  }
  {
    const auto& e = Required(file, root, "initial_pose");
    AttributeReader a(file, e);
    s.initial_pose = {Coordinate(a, "x", geometry_limits), Coordinate(a, "y", geometry_limits),
                      a.Double("theta")};
    a.Finish();
  }
  {
    const auto& e = Required(file, root, "laser");
    AttributeReader a(file, e);
    auto& l = s.laser;
    l.mount = {Coordinate(a, "x", geometry_limits), Coordinate(a, "y", geometry_limits),
               a.Double("theta")};
    l.field_of_view_rad = a.PositiveDouble("field_of_view_rad");
    l.beams = a.IntegerIn<int>("beams", limits.min_beams, limits.max_beams);
    l.rate_hz = a.DoubleIn("rate_hz", limits.min_rate_hz, limits.max_laser_rate_hz);
    l.min_range_m = a.NonNegativeDouble("min_range_m");
    l.max_range_m = a.PositiveDouble("max_range_m");
    l.noise_std_m = a.NonNegativeDouble("noise_std_m");
    l.resolution_m = a.NonNegativeDouble("resolution_m");
    const std::string no_return = a.String("no_return");
    if (no_return != "inf" && no_return != "max") a.Fail("no_return must be inf or max");
    l.no_return_is_max = no_return == "max";
    l.spurious_probability = a.NonNegativeDouble("spurious_probability");
    l.mixed_pixel_probability = a.NonNegativeDouble("mixed_pixel_probability");
    a.Finish();
    if (l.field_of_view_rad > 2 * geometry::kPi + 1e-9) a.Fail("field_of_view_rad must be <= 2 pi");
    if (l.max_range_m <= l.min_range_m) a.Fail("max_range_m must be > min_range_m");
    if (l.spurious_probability > 1 || l.mixed_pixel_probability > 1)
      a.Fail("probabilities must be <= 1");
    config::RequireChildNames(file, e, {"blocked"});
    for (const auto* b = e.FirstChildElement(); b != nullptr; b = b->NextSiblingElement()) {
      AttributeReader ba(file, *b);
      const double from = ba.Double("from_rad"), to = ba.Double("to_rad");
      ba.Finish();
      if (from > to) {
        ba.Fail(
            "from_rad > to_rad: a sector must not wrap through +-pi; write it as two "
            "<blocked> elements, one ending at pi and one starting at -pi");
      }
      l.blocked_sectors.emplace_back(from, to);
    }
  }
  {
    const auto& e = Required(file, root, "path");
    AttributeReader a(file, e);
    const std::string mode = a.String("mode");
    if (mode == "waypoints") {
      s.path.mode = PathSpec::Mode::kWaypoints;
    } else if (mode == "stop_look_move") {
      s.path.mode = PathSpec::Mode::kStopLookMove;
    } else if (mode == "cmd_vel") {
      s.path.mode = PathSpec::Mode::kCmdVel;
    } else {
      a.Fail("mode must be waypoints, stop_look_move or cmd_vel");
    }
    s.path.speed_m_s = a.PositiveDouble("speed_m_s");
    s.path.dwell_s = a.NonNegativeDouble("dwell_s");
    s.path.lookahead_m = a.PositiveDouble("lookahead_m");
    s.path.loop = a.Bool("loop");
    a.Finish();
    s.path.waypoints = ReadWaypoints(file, e, geometry_limits);
    if (s.path.mode != PathSpec::Mode::kCmdVel && s.path.waypoints.empty()) {
      file.Fail(e, "needs at least one <waypoint>");
    }
  }
  if (const auto* obstacles = root.FirstChildElement("obstacles")) {
    config::RequireChildNames(file, *obstacles, {"box", "cylinder", "person"});
    for (const auto* o = obstacles->FirstChildElement(); o != nullptr;
         o = o->NextSiblingElement()) {
      AttributeReader a(file, *o);
      const std::string kind = o->Name();
      if (kind == "box") {
        const Eigen::Vector2d c(Coordinate(a, "x", geometry_limits),
                                Coordinate(a, "y", geometry_limits));
        const double w = Size(a, "width_m", geometry_limits.max_abs_coordinate_m);
        const double h = Size(a, "depth_m", geometry_limits.max_abs_coordinate_m);
        const double yaw = a.Double("theta");
        a.Finish();
        const double cy = std::cos(yaw), sy = std::sin(yaw);
        const Eigen::Vector2d corners[4] = {
            {-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}};
        for (int k = 0; k < 4; ++k) {
          const auto& p = corners[k];
          const auto& q = corners[(k + 1) % 4];
          s.obstacles.segments.push_back(
              {c + Eigen::Vector2d(cy * p.x() - sy * p.y(), sy * p.x() + cy * p.y()),
               c + Eigen::Vector2d(cy * q.x() - sy * q.y(), sy * q.x() + cy * q.y())});
        }
      } else if (kind == "cylinder") {
        s.obstacles.circles.push_back(
            {{Coordinate(a, "x", geometry_limits), Coordinate(a, "y", geometry_limits)},
             Size(a, "radius_m", geometry_limits.max_radius_m)});
        a.Finish();
      } else {
        Person p;
        p.radius_m = Size(a, "radius_m", geometry_limits.max_radius_m);
        p.speed_m_s = a.PositiveDouble("speed_m_s");
        a.Finish();
        p.waypoints = ReadWaypoints(file, *o, geometry_limits);
        if (p.waypoints.size() < 2) file.Fail(*o, "a person needs at least two <waypoint>s");
        s.people.push_back(p);
      }
    }
  }
  return s;
}

}  // namespace structloc::simulation
