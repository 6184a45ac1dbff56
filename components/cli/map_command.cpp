// "structloc map ACTION ...": makes world XML maps from what users have
// (recordings with corrected poses, map_server grids, DXF drawings), turns them
// back into grids, and checks them against recordings. Dispatches to one file
// per action.
#include <cstring>
#include <iostream>

#include "map_subcommands.hpp"

namespace structloc::cli {
namespace {

struct MapAction {
  const char* name;
  const char* selector;  // for "import": the option that picks the importer
  int (*run)(const Invocation&);
  const char* help;
};

const MapAction kActions[] = {
    {"build", nullptr, MapBuildCommand,
     "--log LOG --out WORLD.xml [--plot P.png] ...  walls, corners, pillars from a recording "
     "with corrected poses"},
    {"grid", nullptr, MapGridCommand,
     "--log LOG --out GRID.yaml [--resolution M]  a log-odds occupancy grid ray-cast from a "
     "recording with corrected poses"},
    {"import", "--grid", MapImportGridCommand,
     "--grid MAP.yaml --out WORLD.xml [--plot P.png]  walls, corners, pillars from a map_server "
     "occupancy grid"},
    {"import", "--dxf", MapImportDxfCommand,
     "--dxf DRAWING.dxf --layers L1,L2 --out WORLD.xml [--units mm|cm|m|in|ft] [--plot P.png]  "
     "walls and pillars from a "
     "CAD drawing"},
    {"export", nullptr, MapExportCommand,
     "--map WORLD.xml --grid OUT.yaml [--resolution M]  a map_server grid of a world map"},
    {"check", nullptr, MapCheckCommand,
     "--map WORLD.xml --log LOG [--plot P.png]  how well a map agrees with a recording"},
};

void Usage(std::ostream& out) {
  out << "usage: structloc map ACTION ...  (structloc map ACTION --help lists its options)\n";
  for (const auto& a : kActions) out << "  map " << a.name << " " << a.help << "\n";
}

bool HasArgument(const Invocation& inv, const char* text) {
  for (int i = 3; i < inv.argc; ++i) {
    if (std::strcmp(inv.argv[i], text) == 0) return true;
  }
  return false;
}

}  // namespace

int MapCommand(const Invocation& inv) {
  if (inv.argc < 3 || std::strcmp(inv.argv[2], "--help") == 0) {
    Usage(inv.argc < 3 ? std::cerr : std::cout);
    return inv.argc < 3 ? 2 : 0;
  }
  bool known = false;
  for (const auto& a : kActions) {
    if (std::strcmp(inv.argv[2], a.name) != 0) continue;
    known = true;
    if (a.selector == nullptr || HasArgument(inv, a.selector)) return a.run(inv);
  }
  if (known) {
    std::cerr << "structloc map " << inv.argv[2] << ": say what to import: --grid MAP.yaml or "
              << "--dxf DRAWING.dxf\n";
  } else {
    std::cerr << "structloc map: unknown action '" << inv.argv[2] << "'\n";
  }
  Usage(std::cerr);
  return 2;
}

}  // namespace structloc::cli
