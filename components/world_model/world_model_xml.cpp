// World model XML reader (see header).
#include "structloc/world_model/world_model_xml.hpp"

#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace structloc::world_model {
namespace {

// A point whose coordinates lie within the limits, or a file:line error.
Eigen::Vector2d Point(config::AttributeReader& a, const char* x, const char* y,
                      const WorldLimits& limits) {
  const double bound = limits.max_abs_coordinate_m;
  return {a.DoubleIn(x, -bound, bound), a.DoubleIn(y, -bound, bound)};
}

}  // namespace

WorldModel ReadWorldModel(const config::XmlFile& file, const tinyxml2::XMLElement& world,
                          const WorldLimits& limits) {
  config::AttributeReader world_attrs(file, world);
  const std::string name = world_attrs.String("name");
  world_attrs.Finish();
  config::RequireChildNames(file, world, {"wall", "corner", "cylinder"});
  std::vector<Wall> walls;
  std::vector<Corner> corners;
  std::vector<Cylinder> cylinders;
  for (const auto* e = world.FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    config::AttributeReader a(file, *e);
    const std::string kind = e->Name();
    if (kind == "wall") {
      if (walls.size() == limits.max_walls) {
        a.Fail("more than " + std::to_string(limits.max_walls) +
               " walls: above the walls-per-map limit");
      }
      const int id = a.OptionalIntegerIn<int>("id").value_or(static_cast<int>(walls.size()));
      const Eigen::Vector2d p1 = Point(a, "x1", "y1", limits);
      const Eigen::Vector2d p2 = Point(a, "x2", "y2", limits);
      a.Finish();
      if ((p2 - p1).norm() < 1e-3) a.Fail("zero-length wall (shorter than 1 mm)");
      walls.push_back(MakeWall(id, p1, p2));
    } else if (kind == "corner") {
      Corner c;
      c.id = a.OptionalIntegerIn<int>("id").value_or(static_cast<int>(corners.size()));
      c.position = Point(a, "x", "y", limits);
      a.Finish();
      corners.push_back(c);
    } else {
      Cylinder c;
      c.id = a.OptionalIntegerIn<int>("id").value_or(static_cast<int>(cylinders.size()));
      c.centre = Point(a, "x", "y", limits);
      c.radius = a.PositiveDouble("radius");
      if (c.radius > limits.max_radius_m) {
        std::ostringstream message;
        message << "radius " << std::setprecision(6) << c.radius << " m is above the limit of "
                << limits.max_radius_m << " m";
        a.Fail(message.str());
      }
      a.Finish();
      cylinders.push_back(c);
    }
  }
  try {
    return WorldModel(name, std::move(walls), std::move(corners), std::move(cylinders), {}, limits);
  } catch (const std::invalid_argument& e) {
    file.Fail(world, e.what());
  }
}

WorldModel LoadWorldModel(const std::string& path, const WorldLimits& limits) {
  const auto file = config::XmlFile::Load(path);
  return ReadWorldModel(file, file.Root("world"), limits);
}

}  // namespace structloc::world_model
