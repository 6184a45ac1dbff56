// Reads a world model from XML (schema: maps/world.xsd):
//   <world name="...">
//     <wall x1=".." y1=".." x2=".." y2=".." [id=".."]/>
//     <corner x=".." y=".." [id=".."]/>
//     <cylinder x=".." y=".." radius=".." [id=".."]/>
//   </world>
// Every problem is a config::ConfigError naming file, line and problem.
#pragma once

#include <string>

#include "strict_xml.hpp"
#include "world_model.hpp"

namespace structloc::world {

WorldModel LoadWorldModel(const std::string& path);
// Reads the <world> element of an already opened file (scenario files embed one).
WorldModel ReadWorldModel(const config::XmlFile& file, const tinyxml2::XMLElement& world);

}  // namespace structloc::world
