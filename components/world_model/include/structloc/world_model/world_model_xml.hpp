// Reads a world model from XML (schema: maps/world.xsd):
//   <world name="...">
//     <wall x1=".." y1=".." x2=".." y2=".." [id=".."]/>
//     <corner x=".." y=".." [id=".."]/>
//     <cylinder x=".." y=".." radius=".." [id=".."]/>
//   </world>
// Every problem is a config::ConfigError naming file, line and problem;
// coordinates, radii and the wall count must lie within `limits`.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "structloc/config/strict_xml.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::world_model {

WorldModel LoadWorldModel(const std::string& path, const WorldLimits& limits = {});
// Reads the <world> element of an already opened file (scenario files embed one).
WorldModel ReadWorldModel(const config::XmlFile& file, const tinyxml2::XMLElement& world,
                          const WorldLimits& limits = {});

// Writes `world` in the format LoadWorldModel reads: given walls, given
// (not derived) corners and cylinders, coordinates to 0.1 mm, each element's id.
// `comment_lines` go into an XML comment at the top (what the map was made from,
// with which options), so that a map file says where it came from.
void WriteWorldModel(const WorldModel& world, const std::vector<std::string>& comment_lines,
                     std::ostream& out);

// A length or coordinate as WriteWorldModel writes it (rounded to 0.1 mm), so
// that an importer can check what the file will hold (a wall 1.0001 mm long
// may be written 0.99 mm long, which LoadWorldModel refuses).
double AsWritten(double metres);

}  // namespace structloc::world_model
