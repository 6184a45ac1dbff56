// OpenMP regions on the calling thread alone, for CHOLMOD (see header).
#include "serial_openmp_scope.hpp"

#ifdef STRUCTLOC_WITH_LIBGOMP
#include <omp.h>
#endif

namespace structloc::slam_core::internal {

#ifdef STRUCTLOC_WITH_LIBGOMP
SerialOpenMpScope::SerialOpenMpScope() : saved_levels_(omp_get_max_active_levels()) {
  omp_set_max_active_levels(0);
}

SerialOpenMpScope::~SerialOpenMpScope() {
  omp_set_max_active_levels(saved_levels_);
}
#else
SerialOpenMpScope::SerialOpenMpScope() = default;
SerialOpenMpScope::~SerialOpenMpScope() = default;
#endif

}  // namespace structloc::slam_core::internal
