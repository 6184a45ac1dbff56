// Waiting on a condition instead of sleeping for a guessed time: tests poll
// what they need (a sample arrived, a process printed a line, a file exists)
// and the timeout is only a guard against a hang, set generously so that a
// slow or loaded machine never fails a correct build.
#pragma once

#include <chrono>
#include <functional>
#include <thread>

namespace structloc::testing {

// A failure guard for waits: far longer than any healthy run needs.
constexpr std::chrono::seconds kGenerousTimeout{60};

// Polls `predicate` every 5 ms until it holds (true) or `timeout` passes (false).
inline bool WaitUntil(const std::function<bool()>& predicate,
                      std::chrono::milliseconds timeout = kGenerousTimeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (predicate()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return predicate();
}

}  // namespace structloc::testing
