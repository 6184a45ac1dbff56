// ChildProcess implementation (see header).
#include "structloc/process/child_process.hpp"

#include <fcntl.h>
#include <linux/close_range.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

extern char** environ;

namespace structloc::process {
namespace {

// In the forked child, before exec: only async-signal-safe calls. Reports a
// failure as its errno through `error_pipe` (closed by a successful exec).
[[noreturn]] void ExecChild(const char* path, char* const* argv, char* const* envp, int output_fd,
                            pid_t parent, int error_pipe) {
  int error = 0;
  // A process group of its own, so that a stop reaches what it starts too (a
  // wrapper script's program would otherwise outlive the stop).
  if (setpgid(0, 0) != 0) error = errno;
  if (error == 0 && prctl(PR_SET_PDEATHSIG, SIGTERM) != 0) error = errno;
  // The parent may have died before prctl took effect.
  if (error == 0 && getppid() != parent) _exit(127);
  // The program starts with the stop signals a shell would give it: the
  // launcher's blocked SIGINT/SIGTERM (ShutdownSignal) and a background job's
  // ignored SIGINT are inherited through exec and would leave it deaf to a stop.
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigset_t no_signals;
  sigemptyset(&no_signals);
  if (error == 0 && (sigaction(SIGINT, &default_action, nullptr) != 0 ||
                     sigaction(SIGTERM, &default_action, nullptr) != 0 ||
                     sigprocmask(SIG_SETMASK, &no_signals, nullptr) != 0)) {
    error = errno;
  }
  if (error == 0 && output_fd >= 0) {
    if (dup2(output_fd, STDOUT_FILENO) < 0 || dup2(output_fd, STDERR_FILENO) < 0) error = errno;
  }
  // After the output: with the parent's stdin closed, the output may be fd 0.
  if (error == 0) {
    const int null_fd = open("/dev/null", O_RDONLY);
    if (null_fd < 0 || dup2(null_fd, STDIN_FILENO) < 0) error = errno;
    if (null_fd > STDERR_FILENO) close(null_fd);
  }
  // Nothing else of the parent's may reach the child: its DDS sockets would
  // stay bound, and its shared-memory ports stay open, as long as the child runs.
  if (error == 0 && close_range(3, ~0U, CLOSE_RANGE_CLOEXEC) != 0) {
    // Kernels before 5.11: mark them one by one.
    const long max_fd = sysconf(_SC_OPEN_MAX);
    for (int fd = 3; fd < (max_fd > 0 && max_fd < 65536 ? max_fd : 65536); ++fd) {
      fcntl(fd, F_SETFD, FD_CLOEXEC);
    }
  }
  if (error == 0) {
    execve(path, argv, envp);
    error = errno;
  }
  const ssize_t ignored = write(error_pipe, &error, sizeof(error));
  static_cast<void>(ignored);
  _exit(127);
}

}  // namespace

ChildProcess::ChildProcess(const std::string& executable, const std::vector<std::string>& args,
                           Output output,
                           const std::vector<std::pair<std::string, std::string>>& environment) {
  int fd = -1;
  if (output == Output::kCapture) {
    const char* tmpdir = std::getenv("TMPDIR");
    std::string log_template = std::string(tmpdir != nullptr && *tmpdir != '\0' ? tmpdir : "/tmp") +
                               "/structloc_child_XXXXXX";
    fd = mkstemp(log_template.data());
    if (fd < 0) throw std::runtime_error("cannot create a temp file in " + log_template);
    log_path_ = log_template;
  }
  if (output == Output::kPipe) {
    int ends[2];
    if (pipe2(ends, O_CLOEXEC) != 0) {
      throw std::runtime_error(std::string("cannot create an output pipe: ") +
                               std::strerror(errno));
    }
    pipe_fd_ = ends[0];
    fd = ends[1];
    fcntl(pipe_fd_, F_SETFL, fcntl(pipe_fd_, F_GETFL) | O_NONBLOCK);
  }
  std::vector<std::string> all{executable};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  // The parent's environment with `environment` laid over it, built before
  // fork (the child may only make async-signal-safe calls).
  std::vector<std::string> variables;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry = *e;
    const std::string name = entry.substr(0, entry.find('='));
    bool replaced = false;
    for (const auto& [key, value] : environment) replaced = replaced || key == name;
    if (!replaced) variables.push_back(entry);
  }
  for (const auto& [key, value] : environment) variables.push_back(key + "=" + value);
  std::vector<char*> envp;
  for (auto& v : variables) envp.push_back(v.data());
  envp.push_back(nullptr);
  int error_pipe[2];
  if (pipe2(error_pipe, O_CLOEXEC) != 0) {
    const int error = errno;
    if (fd >= 0) close(fd);
    if (pipe_fd_ >= 0) close(pipe_fd_);
    if (!log_path_.empty()) std::remove(log_path_.c_str());
    throw std::runtime_error("cannot start " + executable + ": " + std::strerror(error));
  }
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ == 0) {
    close(error_pipe[0]);
    ExecChild(executable.c_str(), argv.data(), envp.data(), fd, parent, error_pipe[1]);
  }
  const int fork_error = pid_ < 0 ? errno : 0;
  // Also here, so that the group exists before any signal (the child may not
  // have run yet); EACCES once it has exec'd is harmless, it did it itself.
  if (pid_ > 0) setpgid(pid_, pid_);
  close(error_pipe[1]);
  if (fd >= 0) close(fd);
  int exec_error = fork_error;
  if (pid_ > 0) {
    ssize_t n = 0;
    do {
      n = read(error_pipe[0], &exec_error, sizeof(exec_error));
    } while (n < 0 && errno == EINTR);
    if (n != static_cast<ssize_t>(sizeof(exec_error))) exec_error = 0;  // exec succeeded
  }
  close(error_pipe[0]);
  if (exec_error != 0) {
    if (pid_ > 0) waitpid(pid_, nullptr, 0);
    if (pipe_fd_ >= 0) close(pipe_fd_);
    if (!log_path_.empty()) std::remove(log_path_.c_str());
    throw std::runtime_error("cannot start " + executable + ": " + std::strerror(exec_error));
  }
}

ChildProcess::~ChildProcess() {
  // The child's group: the child if it still runs, and what it started and
  // left behind (the child alone if it has no group).
  if (pid_ > 0 && kill(-pid_, SIGKILL) != 0 && !exit_code_) kill(pid_, SIGKILL);
  if (!exit_code_) waitpid(pid_, nullptr, 0);
  if (!log_path_.empty()) std::remove(log_path_.c_str());
  if (pipe_fd_ >= 0) close(pipe_fd_);
}

void ChildProcess::Signal(int signal_number) const {
  if (exit_code_ || pid_ <= 0) return;
  // The child's whole process group; the child alone if it has none yet.
  if (kill(-pid_, signal_number) != 0) kill(pid_, signal_number);
}

std::optional<int> ChildProcess::Poll() {
  if (exit_code_) return exit_code_;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) == pid_) {
    ending_signal_ = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  return exit_code_;
}

std::optional<int> ChildProcess::WaitExit(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!Poll() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return exit_code_;
}

int ChildProcess::Stop(std::chrono::milliseconds grace) {
  Signal(SIGTERM);
  if (auto code = WaitExit(grace)) return *code;
  Signal(SIGKILL);
  return WaitExit(std::chrono::seconds(5)).value_or(128 + SIGKILL);
}

std::string ChildProcess::ReadAvailable(size_t max_bytes) {
  std::string out;
  if (pipe_fd_ < 0) return out;
  char buffer[4096];
  while (out.size() < max_bytes) {
    const ssize_t n = read(pipe_fd_, buffer, std::min(sizeof buffer, max_bytes - out.size()));
    if (n > 0) {
      out.append(buffer, static_cast<size_t>(n));
    } else if (!(n < 0 && errno == EINTR)) {
      break;  // nothing more now (EAGAIN), or the child closed its end
    }
  }
  return out;
}

std::string ChildProcess::CapturedOutput() const {
  if (log_path_.empty()) return {};
  std::ifstream in(log_path_);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace structloc::process
