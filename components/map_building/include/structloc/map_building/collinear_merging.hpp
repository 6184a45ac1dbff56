// Pieces of one straight wall, as drawings and importers produce them (drawn in
// parts, drawn twice, split by a tool), merged back into one wall: pieces whose
// ends lie within `tolerance` of each other's line and that touch or overlap
// along it within `tolerance`. Each group becomes one wall on the line of its
// longest piece, spanning all pieces, in the place of its first piece; ids are
// renumbered 1..n. DDS-free.
#pragma once

#include <cstddef>
#include <vector>

#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

// Returns how many pieces were merged away; a tolerance <= 0 merges nothing.
size_t MergeCollinear(std::vector<world_model::Wall>& walls, double tolerance);

}  // namespace structloc::map_building
