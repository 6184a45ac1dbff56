// Runs the built `structloc` CLI (or another of our executables) as a real
// child process and returns its exit code and captured output, for tests of
// what a user sees: messages, exit codes and files left behind.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "structloc/process/child_process.hpp"

namespace structloc::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

inline CliResult RunExecutable(const std::string& name, const std::vector<std::string>& args,
                               std::chrono::seconds timeout = std::chrono::seconds(120)) {
  process::ChildProcess child(std::string(STRUCTLOC_BIN_DIR) + "/" + name, args);
  CliResult result;
  const auto code = child.WaitExit(timeout);
  result.exit_code = code ? *code : child.Stop(std::chrono::milliseconds(500));
  result.output = child.CapturedOutput();
  return result;
}

inline CliResult RunCli(const std::vector<std::string>& args,
                        std::chrono::seconds timeout = std::chrono::seconds(120)) {
  return RunExecutable("structloc", args, timeout);
}

}  // namespace structloc::testing
