// Relation files (see header).
#include "structloc/log_formats/relations_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "structloc/config/strict_number.hpp"

namespace structloc::log_formats {

std::vector<Relation> ReadRelations(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  std::vector<Relation> relations;
  std::string line;
  for (size_t n = 1; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    const auto values = config::ParseNumberList(line, 8);
    if (!values || !std::isfinite((*values)[0]) || !std::isfinite((*values)[1])) {
      throw std::runtime_error(path + ":" + std::to_string(n) +
                               ": a relation is eight numbers \"t1 t2 x y z roll pitch yaw\"");
    }
    const auto& v = *values;
    relations.push_back({v[0], v[1], {v[2], v[3], geometry::WrapAngle(v[7])}});
  }
  if (relations.empty()) throw std::runtime_error(path + ": no relation in it");
  return relations;
}

}  // namespace structloc::log_formats
