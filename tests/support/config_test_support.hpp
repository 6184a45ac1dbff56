// Helpers for tests of our strict file readers: write a file into a temporary
// directory, read it, and expect a ConfigError that names the file (with a
// line) and the problem.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "structloc/config/strict_xml.hpp"
#include "temp_dir.hpp"

namespace structloc::testing {

// Writes `text`, calls `read(path)`, expects a ConfigError naming path and `problem`.
inline void ExpectRejected(const std::string& text, const std::string& problem,
                           const std::function<void(const std::string&)>& read) {
  const TempDir temp;
  const std::string path = temp.Write("rejected.xml", text);
  try {
    read(path);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const config::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path + ":"), std::string::npos) << what;
    EXPECT_NE(what.find(problem), std::string::npos) << what;
  }
}

}  // namespace structloc::testing
