// Test helper: a localisation parameter file whole (every section and key, as
// `structloc params --expand` prints it), for tests that edit one key of a
// complete file: the shipped presets state only what differs from the
// defaults.
#pragma once

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "structloc/localisation_core/tracking/tracking_session_options.hpp"
#include "temp_dir.hpp"

namespace structloc::testing {

inline std::string WholeParamsText(const std::string& path) {
  std::ostringstream whole;
  localisation_core::WriteExpandedLocalisationParams(path, whole);
  return whole.str();
}

// The file at `path` whole with its first `from` replaced by `to` (which must
// occur), written into `dir` as `name`; returns the path written.
inline std::string EditedWholeParams(const TempDir& dir, const std::string& path,
                                     const std::string& from, const std::string& to,
                                     const std::string& name = "params.xml") {
  std::string text = WholeParamsText(path);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from << " not in\n" << text;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return dir.Write(name, text);
}

}  // namespace structloc::testing
