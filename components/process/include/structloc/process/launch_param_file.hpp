// ROS 2 parameter files for launch files' <param from="FILE"/>: the
// ros__parameters of the entries that match a node, as ros2 launch applies
// them. A file holds entries keyed by "/**" (every node), the node's name or
// its name with its namespace ("robot1/localisation", with or without a
// leading '/'), each with one "ros__parameters" map of plain values:
//   /**:
//     ros__parameters:
//       domain: 3
//   robot1/localisation:
//     ros__parameters:
//       initial-pose: "2.0 6.5 0"
// Keys are the component's options (as in <param name="...">); entries for
// other nodes are skipped; "/**" comes first, so a node's own entry wins.
// DDS-free.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace structloc::process {

// The parameters for the node `qualified_name` ("ns/name" or "name"), in the
// file's order. Throws config::ConfigError naming the file, the line and the
// problem (unreadable file, malformed YAML, an entry without ros__parameters,
// a value that is a list or a map, a key that is not a plain name, a node
// entry or parameter name given twice). Linear in the file's size, aliases
// included (each entry and parameter is visited once).
std::vector<std::pair<std::string, std::string>> ReadNodeParameters(
    const std::string& path, const std::string& qualified_name);

}  // namespace structloc::process
