// One way for the map makers to refuse a bad option: std::invalid_argument
// "<subject> option <what>", naming the option in `what`. DDS-free.
#pragma once

#include <stdexcept>
#include <string>

namespace structloc::map_building {

inline void RequireOption(bool ok, const char* subject, const std::string& what) {
  if (!ok) throw std::invalid_argument(std::string(subject) + " option " + what);
}

}  // namespace structloc::map_building
