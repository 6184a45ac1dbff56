// Clean stop on SIGINT/SIGTERM without a global flag: the signals are blocked
// in the constructing thread (before DDS starts its threads, which inherit the
// mask) and collected synchronously with sigtimedwait.
#pragma once

#include <chrono>

namespace structloc::process {

class ShutdownSignal {
 public:
  // Construct first thing in main(), before any thread exists.
  ShutdownSignal();
  // Waits up to `timeout`; true once SIGINT or SIGTERM has arrived.
  bool WaitFor(std::chrono::milliseconds timeout);
  bool Received() const { return received_; }

 private:
  bool received_ = false;
};

}  // namespace structloc::process
