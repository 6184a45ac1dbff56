// Helpers for tests of our strict file readers: write a temp file, read it,
// and expect a ConfigError that names the file (with a line) and the problem.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <string>

#include "strict_xml.hpp"

namespace structloc::testing {

inline std::string WriteTempFile(const std::string& text, const std::string& suffix = ".xml") {
  static int counter = 0;
  const std::string path =
      "/tmp/structloc_test_" + std::to_string(getpid()) + "_" + std::to_string(counter++) + suffix;
  std::ofstream(path) << text;
  return path;
}

// Writes `text`, calls `read(path)`, expects a ConfigError naming path and `problem`.
inline void ExpectRejected(const std::string& text, const std::string& problem,
                           const std::function<void(const std::string&)>& read) {
  const std::string path = WriteTempFile(text);
  try {
    read(path);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const config::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path + ":"), std::string::npos) << what;
    EXPECT_NE(what.find(problem), std::string::npos) << what;
  }
  std::remove(path.c_str());
}

}  // namespace structloc::testing
