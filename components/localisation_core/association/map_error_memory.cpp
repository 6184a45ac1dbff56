// How often each map feature was fused recently (see header).
#include "structloc/localisation_core/association/map_error_memory.hpp"

#include <cmath>

namespace structloc::localisation_core {

void MapErrorMemory::Reset(size_t features, double travel_m) {
  travel_m_ = travel_m > 0.0 ? travel_m : 0.0;
  uses_.assign(Enabled() ? features : 0, 0.0);
}

void MapErrorMemory::Travel(double metres) {
  if (!Enabled() || !(metres > 0.0)) return;
  const double fade = std::isfinite(metres) ? std::exp(-metres / travel_m_) : 0.0;
  for (double& u : uses_) u *= fade;
}

double MapErrorMemory::MapErrorScale(int slot) const {
  if (slot < 0 || static_cast<size_t>(slot) >= uses_.size()) return 1.0;
  return 1.0 + uses_[static_cast<size_t>(slot)];
}

void MapErrorMemory::RememberFused(int slot) {
  if (slot < 0 || static_cast<size_t>(slot) >= uses_.size()) return;
  uses_[static_cast<size_t>(slot)] += 1.0;
}

}  // namespace structloc::localisation_core
