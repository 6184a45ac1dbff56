// Changed copies of shipped files for tests: the text of a file under maps/
// (a scenario, say) with its references to other shipped files made
// absolute, so that the copy can be written anywhere.
#pragma once

#include <string>

#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc::testing {

// The shipped file's text with every file="../..." made absolute.
inline std::string ShippedTextForCopy(const std::string& relative) {
  std::string text = ReadFile(SourcePath(relative));
  for (size_t pos = 0; (pos = text.find("file=\"../", pos)) != std::string::npos;) {
    text.replace(pos, 9, "file=\"" + SourcePath("maps/"));
  }
  return text;
}

}  // namespace structloc::testing
