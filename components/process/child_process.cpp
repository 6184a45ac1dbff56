// ChildProcess implementation (see header).
#include "child_process.hpp"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace structloc::process {

ChildProcess::ChildProcess(const std::string& executable, const std::vector<std::string>& args,
                           Output output) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  int fd = -1;
  if (output == Output::kCapture) {
    char log_template[] = "/tmp/structloc_child_XXXXXX";
    fd = mkstemp(log_template);
    if (fd < 0) throw std::runtime_error("cannot create a temp file for " + executable);
    log_path_ = log_template;
    posix_spawn_file_actions_adddup2(&actions, fd, STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, fd, STDERR_FILENO);
  }
  std::vector<std::string> all{executable};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int rc = posix_spawn(&pid_, executable.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (fd >= 0) close(fd);
  if (rc != 0) {
    if (!log_path_.empty()) std::remove(log_path_.c_str());
    throw std::runtime_error("cannot start " + executable + ": " + std::to_string(rc));
  }
}

ChildProcess::~ChildProcess() {
  if (!exit_code_) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  if (!log_path_.empty()) std::remove(log_path_.c_str());
}

void ChildProcess::Signal(int signal_number) const {
  if (!exit_code_) kill(pid_, signal_number);
}

std::optional<int> ChildProcess::Poll() {
  if (exit_code_) return exit_code_;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) == pid_) {
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

std::string ChildProcess::CapturedOutput() const {
  if (log_path_.empty()) return {};
  std::ifstream in(log_path_);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace structloc::process
