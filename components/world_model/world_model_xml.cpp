// World model XML reader (see header).
#include "world_model_xml.hpp"

#include <stdexcept>

namespace structloc::world {

WorldModel ReadWorldModel(const config::XmlFile& file, const tinyxml2::XMLElement& world) {
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
      const int id =
          static_cast<int>(a.OptionalInteger("id").value_or(static_cast<long long>(walls.size())));
      const Eigen::Vector2d p1(a.Double("x1"), a.Double("y1"));
      const Eigen::Vector2d p2(a.Double("x2"), a.Double("y2"));
      a.Finish();
      if ((p2 - p1).norm() < 1e-3) a.Fail("zero-length wall (shorter than 1 mm)");
      walls.push_back(MakeWall(id, p1, p2));
    } else if (kind == "corner") {
      Corner c;
      c.id = static_cast<int>(
          a.OptionalInteger("id").value_or(static_cast<long long>(corners.size())));
      c.position = {a.Double("x"), a.Double("y")};
      a.Finish();
      corners.push_back(c);
    } else {
      Cylinder c;
      c.id = static_cast<int>(
          a.OptionalInteger("id").value_or(static_cast<long long>(cylinders.size())));
      c.centre = {a.Double("x"), a.Double("y")};
      c.radius = a.PositiveDouble("radius");
      a.Finish();
      cylinders.push_back(c);
    }
  }
  try {
    return WorldModel(name, std::move(walls), std::move(corners), std::move(cylinders));
  } catch (const std::invalid_argument& e) {
    file.Fail(world, e.what());
  }
}

WorldModel LoadWorldModel(const std::string& path) {
  const auto file = config::XmlFile::Load(path);
  return ReadWorldModel(file, file.Root("world"));
}

}  // namespace structloc::world
