// Reads a world model from XML (schema: maps/world.xsd):
//   <world name="...">
//     <wall x1=".." y1=".." x2=".." y2=".." [id=".."]/>
//     <corner x=".." y=".." [id=".."]/>
//     <cylinder x=".." y=".." radius=".." [id=".."]/>
//   </world>
// Every problem is a config::ConfigError naming file, line and problem;
// coordinates, radii and the wall count must lie within `limits`.
#pragma once

#include <string>

#include "structloc/config/strict_xml.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::world_model {

WorldModel LoadWorldModel(const std::string& path, const WorldLimits& limits = {});
// Reads the <world> element of an already opened file (scenario files embed one).
WorldModel ReadWorldModel(const config::XmlFile& file, const tinyxml2::XMLElement& world,
                          const WorldLimits& limits = {});

}  // namespace structloc::world_model
