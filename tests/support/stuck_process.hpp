// Why a component a test waited for did not answer: how it ended, or, when it
// is still running, its threads' stacks (from gdb, which the test setup
// installs), so that a failure seen once in CI says where it was stuck.
#pragma once

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstring>
#include <string>

#include "structloc/process/child_process.hpp"

namespace structloc::testing {

inline std::string WhyUnresponsive(process::ChildProcess& child) {
  if (const auto code = child.Poll()) {
    return *code > 128 ? "it died of signal " + std::to_string(*code - 128) + " (" +
                             strsignal(*code - 128) + ")"
                       : "it exited with status " + std::to_string(*code);
  }
  const char* gdb = "/usr/bin/gdb";
  if (access(gdb, X_OK) != 0) return "it is still running (install gdb to see where it waits)";
  process::ChildProcess stacks(
      gdb, {"-p", std::to_string(child.Pid()), "-batch", "-ex", "thread apply all bt"});
  if (!stacks.WaitExit(std::chrono::seconds(60))) stacks.Signal(SIGKILL);
  return "it is still running; its threads:\n" + stacks.CapturedOutput();
}

}  // namespace structloc::testing
