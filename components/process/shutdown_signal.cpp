// ShutdownSignal: synchronous signal collection (see header).
#include "structloc/process/shutdown_signal.hpp"

#include <pthread.h>
#include <signal.h>

#include <cerrno>
#include <ctime>

namespace structloc::process {
namespace {
sigset_t StopSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}
}  // namespace

ShutdownSignal::ShutdownSignal() {
  // A program started in the background by a shell has SIGINT ignored, and an
  // ignored signal is discarded even while blocked: take both back to default
  // (never acted on while blocked) so that sigtimedwait sees them.
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigaction(SIGINT, &default_action, nullptr);
  sigaction(SIGTERM, &default_action, nullptr);
  const sigset_t set = StopSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

bool ShutdownSignal::WaitFor(std::chrono::milliseconds timeout) {
  if (received_) return true;
  const sigset_t set = StopSignals();
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(timeout.count() / 1000);
  ts.tv_nsec = static_cast<long>((timeout.count() % 1000) * 1000000L);
  const int sig = sigtimedwait(&set, nullptr, &ts);
  if (sig == SIGINT || sig == SIGTERM) received_ = true;
  return received_;
}

}  // namespace structloc::process
