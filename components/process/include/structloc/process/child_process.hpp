// One child process of ours: started with fork and exec in a process group of
// its own (signals reach the processes it starts too), stdin from /dev/null
// (a background group reading the terminal would be stopped), output either
// inherited or captured to a temp file, always reaped (SIGKILL to its group in
// the destructor if it is still running), and sent SIGTERM by the kernel when the
// thread that started it dies (PR_SET_PDEATHSIG), so that neither a launcher
// killed with SIGKILL nor a failing test leaves processes behind. DDS-free.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace structloc::process {

class ChildProcess {
 public:
  // kInherit: the parent's stdout/stderr; kCapture: a temp file
  // (CapturedOutput); kPipe: a pipe the parent reads with ReadAvailable.
  enum class Output { kInherit, kCapture, kPipe };
  // Throws std::runtime_error ("cannot start PATH: No such file or directory")
  // when the executable cannot be started. Start children from a thread that
  // lives as long as they should (the main thread): they stop when it ends.
  // `environment` is added to (or replaces variables of) the parent's.
  ChildProcess(const std::string& executable, const std::vector<std::string>& args,
               Output output = Output::kCapture,
               const std::vector<std::pair<std::string, std::string>>& environment = {});
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  void Signal(int signal_number) const;
  // Non-blocking check; the exit code once ended (128+signal when killed).
  std::optional<int> Poll();
  // The signal that ended it; 0 while it runs or when it exited by itself
  // (an exit code of 137 is not signal 9).
  int EndingSignal() const { return ending_signal_; }
  std::optional<int> WaitExit(std::chrono::milliseconds timeout);
  // SIGTERM, then SIGKILL after `grace`; returns the exit code.
  int Stop(std::chrono::milliseconds grace);
  // Captured stdout+stderr so far (empty when output is inherited).
  std::string CapturedOutput() const;
  // kPipe: the stdout+stderr bytes written since the last call, at most
  // `max_bytes` of them (a node writing without pause would otherwise keep
  // the reader here, its memory growing), without waiting.
  std::string ReadAvailable(size_t max_bytes = 64 * 1024);
  pid_t Pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  std::string log_path_;
  int pipe_fd_ = -1;  // kPipe: the read end
  std::optional<int> exit_code_;
  int ending_signal_ = 0;
};

}  // namespace structloc::process
