// SerialOpenMpScope keeps CHOLMOD's OpenMP teams on the solving thread: a
// region asking for four threads gets one inside the scope, four after it.
#include "serial_openmp_scope.hpp"

#include <gtest/gtest.h>
#include <omp.h>

namespace structloc::slam_core::internal {
namespace {

int TeamSizeAskingForFour() {
  int size = 0;
#pragma omp parallel num_threads(4)
  {
#pragma omp single
    size = omp_get_num_threads();
  }
  return size;
}

TEST(SerialOpenMpScope, RegionsInsideRunOnTheCallingThreadAlone) {
  omp_set_dynamic(0);  // a region gets the threads it asks for (OMP_DYNAMIC aside)
  const int levels = omp_get_max_active_levels();
  {
    const SerialOpenMpScope scope;
    EXPECT_EQ(TeamSizeAskingForFour(), 1);
  }
  EXPECT_EQ(omp_get_max_active_levels(), levels);
  EXPECT_EQ(TeamSizeAskingForFour(), 4);
}

}  // namespace
}  // namespace structloc::slam_core::internal
