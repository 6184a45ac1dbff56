// Scenario XML reader (see scenario.hpp; schema in maps/scenarios/README.md).
// The elements' attributes are declared in scenario_options.cpp; lists and
// file references are read here.
#include <cmath>
#include <filesystem>

#include "structloc/config/strict_xml.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "structloc/simulation_core/scenario_options.hpp"
#include "structloc/world_model/world_model_xml.hpp"

namespace structloc::simulation_core {
namespace {

using config::AttributeReader;
using config::XmlFile;

// A map-frame coordinate within the world limits (the message names the bound).
double Coordinate(AttributeReader& a, const char* name, const world_model::WorldLimits& limits) {
  return a.DoubleIn(name, -limits.max_abs_coordinate_m, limits.max_abs_coordinate_m);
}

// A size or radius in (0, limit].
double Size(AttributeReader& a, const char* name, double limit) {
  const double value = a.DoubleIn(name, 0.0, limit);
  if (!(value > 0.0)) a.Fail(std::string("attribute ") + name + " must be > 0");
  return value;
}

std::vector<Eigen::Vector2d> ReadWaypoints(const XmlFile& file, const tinyxml2::XMLElement& parent,
                                           const world_model::WorldLimits& limits) {
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

// <laser> with its blocked sectors (none may wrap through +-pi).
void ReadLaser(const XmlFile& file, const tinyxml2::XMLElement& e, const ScenarioLimits& limits,
               LaserSpec& l) {
  LaserAttributes(limits).Load(file, e, l);
  if (l.max_range_m <= l.min_range_m) file.Fail(e, "laser: max_range_m must be > min_range_m");
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

// The <teleport>s, in time order, each naming a waypoint of the path.
void ReadTeleports(const XmlFile& file, const tinyxml2::XMLElement& root,
                   const world_model::WorldLimits& limits, Scenario& s) {
  for (const auto* t = root.FirstChildElement("teleport"); t != nullptr;
       t = t->NextSiblingElement("teleport")) {
    AttributeReader a(file, *t);
    Teleport teleport;
    teleport.at_s = a.DoubleIn("at_s", 0.0, s.duration_s);
    teleport.pose = {Coordinate(a, "x", limits), Coordinate(a, "y", limits),
                     a.DoubleIn("theta", -geometry::kPi, geometry::kPi)};
    const double next = a.DoubleIn("next_waypoint", 0.0, 1e6);
    a.Finish();
    if (next != std::floor(next) || next >= static_cast<double>(s.path.waypoints.size())) {
      file.Fail(*t, "next_waypoint must be the index of one of the path's " +
                        std::to_string(s.path.waypoints.size()) + " waypoints");
    }
    teleport.next_waypoint = static_cast<size_t>(next);
    if (!s.teleports.empty() && teleport.at_s <= s.teleports.back().at_s)
      file.Fail(*t, "teleports must be in time order");
    s.teleports.push_back(teleport);
  }
}

// A <box>: its four sides as segments.
void ReadBox(AttributeReader& a, const world_model::WorldLimits& limits,
             world_model::Scene& obstacles) {
  const Eigen::Vector2d c(Coordinate(a, "x", limits), Coordinate(a, "y", limits));
  const double w = Size(a, "width_m", limits.max_abs_coordinate_m);
  const double h = Size(a, "depth_m", limits.max_abs_coordinate_m);
  const double yaw = a.Double("theta");
  a.Finish();
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  const Eigen::Vector2d corners[4] = {
      {-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}};
  for (int k = 0; k < 4; ++k) {
    const auto& p = corners[k];
    const auto& q = corners[(k + 1) % 4];
    obstacles.segments.push_back(
        {c + Eigen::Vector2d(cy * p.x() - sy * p.y(), sy * p.x() + cy * p.y()),
         c + Eigen::Vector2d(cy * q.x() - sy * q.y(), sy * q.x() + cy * q.y())});
  }
}

// <obstacles>: boxes, cylinders and people walking their waypoints.
void ReadObstacles(const XmlFile& file, const tinyxml2::XMLElement& obstacles,
                   const world_model::WorldLimits& limits, Scenario& s) {
  config::RequireChildNames(file, obstacles, {"box", "cylinder", "person"});
  const auto person_attributes = PersonAttributes(limits);
  for (const auto* o = obstacles.FirstChildElement(); o != nullptr; o = o->NextSiblingElement()) {
    const std::string kind = o->Name();
    if (kind == "person") {
      Person p;
      person_attributes.Load(file, *o, p);
      p.waypoints = ReadWaypoints(file, *o, limits);
      if (p.waypoints.size() < 2) file.Fail(*o, "a person needs at least two <waypoint>s");
      s.people.push_back(p);
      continue;
    }
    AttributeReader a(file, *o);
    if (kind == "box") {
      ReadBox(a, limits, s.obstacles);
    } else {
      s.obstacles.circles.push_back({{Coordinate(a, "x", limits), Coordinate(a, "y", limits)},
                                     Size(a, "radius_m", limits.max_radius_m)});
      a.Finish();
    }
  }
}

}  // namespace

kinematics::RobotParameters Scenario::TrueParameters() const {
  kinematics::RobotParameters p = nominal;
  p.wheel_radius *= errors.wheel_radius_scale;
  p.axle_distance *= errors.axle_distance_scale;
  p.steering_offset += errors.steering_offset_rad;
  p.left_wheel_radius *= errors.left_wheel_radius_scale;
  p.right_wheel_radius *= errors.right_wheel_radius_scale;
  p.wheel_separation *= errors.wheel_separation_scale;
  return p;
}

Scenario LoadScenario(const std::string& path, const ScenarioLimits& limits) {
  const auto& geometry_limits = limits.world;
  const auto file = XmlFile::Load(path);
  const auto& root = file.Root("scenario");
  config::RequireChildNames(
      file, root,
      {"world", "robot", "true_robot", "initial_pose", "laser", "path", "obstacles", "teleport"});
  Scenario s;
  ScenarioAttributes(limits).Load(file, root, s);
  {
    const auto& e = Required(file, root, "world");
    AttributeReader a(file, e);
    s.world_path = Resolve(path, a.String("file"));
    a.Finish();
    s.world = std::make_shared<world_model::WorldModel>(
        world_model::LoadWorldModel(s.world_path, geometry_limits));
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
    TrueRobotAttributes(s.nominal.traction_counter_bits).Load(file, e, s.errors);
  }
  InitialPoseAttributes(geometry_limits)
      .Load(file, Required(file, root, "initial_pose"), s.initial_pose);
  ReadLaser(file, Required(file, root, "laser"), limits, s.laser);
  {
    const auto& e = Required(file, root, "path");
    PathAttributes().Load(file, e, s.path);
    s.path.waypoints = ReadWaypoints(file, e, geometry_limits);
    if (s.path.mode != PathSpec::Mode::kCmdVel && s.path.waypoints.empty()) {
      file.Fail(e, "needs at least one <waypoint>");
    }
  }
  ReadTeleports(file, root, geometry_limits, s);
  if (const auto* obstacles = root.FirstChildElement("obstacles"))
    ReadObstacles(file, *obstacles, geometry_limits, s);
  return s;
}

}  // namespace structloc::simulation_core
