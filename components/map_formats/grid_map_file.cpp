// map_server grid files: not written yet.
#include "structloc/map_formats/grid_map_file.hpp"

#include <stdexcept>

namespace structloc::map_formats {

map_building::OccupancyGrid LoadGridMap(const std::string&) {
  throw std::runtime_error("not written yet");
}

void SaveGridMap(const map_building::OccupancyGrid&, const std::string&,
                 const std::vector<std::string>&) {
  throw std::runtime_error("not written yet");
}

}  // namespace structloc::map_formats
