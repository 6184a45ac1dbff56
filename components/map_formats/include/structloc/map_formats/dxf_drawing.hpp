// CAD drawings in DXF, as architects and integrators exchange floor plans:
// the model-space LINE, LWPOLYLINE, POLYLINE (with its VERTEX entities),
// CIRCLE, ARC and POINT entities with their layers, the layer table and the
// header's $INSUNITS, read with dxflib (DL_Dxf and a DL_CreationAdapter).
// Entities of other kinds are counted per layer so that an import can say what
// it left out. Block definitions and paper space are not read. DDS-free.
#pragma once

#include <string>

#include "structloc/map_building/dxf_import.hpp"

namespace structloc::map_formats {

// Throws config::ConfigError naming the file and what is wrong: missing,
// a folder, unreadable, binary DXF, not a DXF at all (no section dxflib could
// find), or a drawing without entities.
map_building::CadDrawing ReadDxfDrawing(const std::string& path);

}  // namespace structloc::map_formats
