// "structloc map check": not written yet.
#include <iostream>

#include "map_subcommands.hpp"

namespace structloc::cli {

int MapCheckCommand(const Invocation&) {
  std::cerr << "structloc map: not written yet\n";
  return 2;
}

}  // namespace structloc::cli
