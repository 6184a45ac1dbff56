// One child process of ours: started with posix_spawn, output either inherited
// or captured to a temp file, always reaped (SIGKILL in the destructor if it is
// still running) so that neither the launcher nor a failing test leaves
// processes behind. DDS-free.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace structloc::process {

class ChildProcess {
 public:
  enum class Output { kInherit, kCapture };
  // Throws std::runtime_error when the executable cannot be started.
  ChildProcess(const std::string& executable, const std::vector<std::string>& args,
               Output output = Output::kCapture);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  void Signal(int signal_number) const;
  // Non-blocking check; the exit code once ended (128+signal when killed).
  std::optional<int> Poll();
  std::optional<int> WaitExit(std::chrono::milliseconds timeout);
  // SIGTERM, then SIGKILL after `grace`; returns the exit code.
  int Stop(std::chrono::milliseconds grace);
  // Captured stdout+stderr so far (empty when output is inherited).
  std::string CapturedOutput() const;
  pid_t Pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  std::string log_path_;
  std::optional<int> exit_code_;
};

}  // namespace structloc::process
