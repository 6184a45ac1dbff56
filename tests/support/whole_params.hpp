// Test helper: a localisation parameter file whole (every section and key, as
// `structloc params --expand` prints it), for tests that edit one key of a
// complete file: the shipped presets state only what differs from the
// defaults.
#pragma once

#include <sstream>
#include <string>

#include "structloc/localisation_core/tracking/tracking_session_options.hpp"

namespace structloc::testing {

inline std::string WholeParamsText(const std::string& path) {
  std::ostringstream whole;
  localisation_core::WriteExpandedLocalisationParams(path, whole);
  return whole.str();
}

}  // namespace structloc::testing
