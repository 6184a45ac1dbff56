// Paths of the source tree and the built executables, for tests (DDS-free).
#pragma once

#include <string>

namespace structloc::testing {

inline std::string SourcePath(const std::string& relative) {
  return std::string(STRUCTLOC_SOURCE_DIR) + "/" + relative;
}

}  // namespace structloc::testing
