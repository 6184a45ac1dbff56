// The thread's CPU clock (see stage_timings.hpp).
#include "structloc/localisation_core/localiser/stage_timings.hpp"

#include <time.h>

namespace structloc::localisation_core {

double ThreadCpuMicroseconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e6 * static_cast<double>(t.tv_sec) + 1e-3 * static_cast<double>(t.tv_nsec);
}

}  // namespace structloc::localisation_core
