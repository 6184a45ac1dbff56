// Fuzz-target helper: the parsers read files, so each input is written to a
// folder of this process's own (structloc-fuzz-PID under $TMPDIR or /tmp; the
// run script points TMPDIR at a folder it removes) under the name the parser
// expects, and the parser runs on that path. Expected refusals
// (exceptions a user sees as error messages) are the parser doing its job;
// only crashes, sanitizer findings, hangs and unbounded memory are findings.
#pragma once

#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

namespace structloc::fuzz {

// This process's folder for input files.
inline const std::string& InputFolder() {
  static const std::string folder = [] {
    const char* tmp = std::getenv("TMPDIR");
    const std::string path = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") +
                             "/structloc-fuzz-" + std::to_string(getpid());
    mkdir(path.c_str(), 0700);
    return path;
  }();
  return folder;
}

// Writes `size` bytes to the file NAME (e.g. "world.xml") in this process's
// folder and returns its path.
inline std::string WriteFile(const std::string& name, const void* data, size_t size) {
  const std::string path = InputFolder() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

inline std::string WriteInput(const uint8_t* data, size_t size, const std::string& name) {
  return WriteFile(name, data, size);
}

// Runs `parse`: an exception is a refusal a user would see as an error
// message, the parser doing its job; anything else is for libFuzzer to catch.
template <class F>
void Parse(F parse) {
  try {
    parse();
  } catch (const std::exception&) {
  }
}

}  // namespace structloc::fuzz
