// Launch runner (see header).
#include "structloc/process/launch_runner.hpp"

#include <algorithm>
#include <csignal>
#include <cstring>
#include <iostream>
#include <memory>
#include <thread>
#include <vector>

#include "structloc/process/child_process.hpp"

namespace structloc::process {
namespace {

using Clock = std::chrono::steady_clock;

// "exit code 3", or "signal 9 (Killed)" for a child a signal ended.
std::string DescribeExit(const ChildProcess& child, int code) {
  if (const int signal = child.EndingSignal()) {
    return "signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
  }
  return "exit code " + std::to_string(code);
}

// One node of the launch: its process while it runs, when to start it again,
// and the part of an output line it has not finished yet.
struct Running {
  std::unique_ptr<ChildProcess> child;
  std::optional<Clock::time_point> restart_at;
  int respawns = 0;
  std::string partial_line;
};

// Prints what the node wrote since the last call, each line prefixed with
// "[name] " as ros2 launch does; with `flush`, or once longer than 64 KiB,
// the unfinished line too.
void Relay(const NodeLaunch& node, Running& running, bool flush) {
  if (!running.child) return;
  // At most 64 KiB per poll (a chatty node is relayed a piece each time, and
  // the launcher keeps its pace); at the end, what the pipe still holds.
  constexpr size_t kPerPoll = 64 * 1024, kAtTheEnd = 1024 * 1024;
  running.partial_line += running.child->ReadAvailable(flush ? kAtTheEnd : kPerPoll);
  size_t start = 0;
  for (size_t end; (end = running.partial_line.find('\n', start)) != std::string::npos;
       start = end + 1) {
    std::cout << "[" << node.name << "] " << running.partial_line.substr(start, end - start)
              << "\n";
  }
  running.partial_line.erase(0, start);
  // A node that never ends its line must not make the launcher's memory grow.
  constexpr size_t kLongestLine = 64 * 1024;
  if ((flush || running.partial_line.size() > kLongestLine) && !running.partial_line.empty()) {
    std::cout << "[" << node.name << "] " << running.partial_line << "\n";
    running.partial_line.clear();
  }
  std::cout << std::flush;
}

// Starts the node; false (and the reason on stderr) when it cannot be started
// (its executable removed or no longer executable, no processes left), so
// that the launch stops the nodes it did start as after any other failure.
bool Start(const NodeLaunch& node, Running& running) {
  std::cout << "[launch] starting " << node.name << ": ";
  for (const auto& [name, value] : node.environment) std::cout << name << "=" << value << " ";
  std::cout << node.executable;
  for (const auto& a : node.arguments) std::cout << " " << a;
  std::cout << std::endl;
  running.restart_at.reset();
  try {
    running.child = std::make_unique<ChildProcess>(node.executable, node.arguments,
                                                   ChildProcess::Output::kPipe, node.environment);
  } catch (const std::exception& e) {
    std::cerr << "[launch] ERROR: " << node.name << ": " << e.what() << ": stopping the launch"
              << std::endl;
    return false;
  }
  std::cout << "[launch] " << node.name << " has pid " << running.child->Pid() << std::endl;
  return true;
}

// Why the launch ends, and with which result so far.
struct LaunchEnd {
  bool ended = false;
  std::string reason = "stop signal";
  int result = 0;
};

// One poll of a running node: its output relayed; ended, it is respawned
// later (respawn="true") or it ends the launch (failed when it died).
void Watch(const NodeLaunch& node, Running& running, Clock::time_point now, LaunchEnd& end) {
  const auto code = running.child->Poll();
  Relay(node, running, code.has_value());
  if (!code) return;
  if (node.respawn) {
    std::cout << "[launch] " << node.name << " ended with " << DescribeExit(*running.child, *code)
              << "; respawning in " << node.respawn_delay_s << " s" << std::endl;
    running.child.reset();
    running.restart_at =
        now + std::chrono::microseconds(static_cast<long>(node.respawn_delay_s * 1e6));
    return;
  }
  // A node that finished its job ends the launch; one that died fails it.
  end.reason = node.name + " ended with " + DescribeExit(*running.child, *code);
  if (*code != 0) {
    std::cerr << "[launch] ERROR: " << node.name << " died with "
              << DescribeExit(*running.child, *code)
              << " and has no respawn=\"true\": stopping the launch" << std::endl;
    end.result = 1;
  }
  end.ended = true;
}

// Starts every node and keeps them running (respawning those that ask for
// it) until a stop signal, the duration, or a node that ends the launch.
LaunchEnd Supervise(const LaunchDescription& description, const LaunchRunOptions& options,
                    ShutdownSignal& shutdown, std::vector<Running>& nodes) {
  const auto start = Clock::now();
  LaunchEnd end;
  // A node that cannot be (re)started fails the launch, as one that dies does.
  const auto start_or_fail = [&](const NodeLaunch& node, Running& running, const char* what) {
    if (Start(node, running)) return;
    end = {true, node.name + " could not be " + what, 1};
  };
  for (size_t i = 0; i < nodes.size() && !end.ended; ++i) {
    start_or_fail(description.nodes[i], nodes[i], "started");
  }
  while (!end.ended && !shutdown.WaitFor(std::chrono::milliseconds(50))) {
    const auto now = Clock::now();
    for (size_t i = 0; i < nodes.size() && !end.ended; ++i) {
      Running& running = nodes[i];
      if (!running.restart_at) {
        Watch(description.nodes[i], running, now, end);
      } else if (now >= *running.restart_at) {
        ++running.respawns;
        start_or_fail(description.nodes[i], running, "respawned");
      }
    }
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    if (!end.ended && options.duration_s && elapsed >= *options.duration_s) {
      end.reason = "duration of " + std::to_string(*options.duration_s) + " s reached";
      end.ended = true;
    }
  }
  return end;
}

// As ros2 launch does: SIGINT to every node at once, SIGTERM to those still
// running after the grace, SIGKILL to those still running 2 s later; all
// nodes together, their output relayed all the while (a node writing much
// as it stops must not block on a full pipe). Returns the last signal sent
// to each node (0: none).
std::vector<int> StopAll(const LaunchDescription& description, const LaunchRunOptions& options,
                         std::vector<Running>& nodes) {
  const double escalation_s[] = {options.stop_grace_s, 2.0, 5.0};
  const int escalation_signal[] = {SIGINT, SIGTERM, SIGKILL};
  std::vector<int> stopped_by(nodes.size(), 0);
  for (int step = 0; step < 3; ++step) {
    bool any = false;
    for (size_t i = 0; i < nodes.size(); ++i) {
      if (!nodes[i].child || nodes[i].child->Poll()) continue;  // none while waiting to respawn
      nodes[i].child->Signal(escalation_signal[step]);
      stopped_by[i] = escalation_signal[step];
      any = true;
    }
    if (!any) break;
    const auto deadline =
        Clock::now() + std::chrono::milliseconds(static_cast<long>(escalation_s[step] * 1000));
    for (bool running = true; running && Clock::now() < deadline;) {
      running = false;
      for (size_t i = 0; i < nodes.size(); ++i) {
        if (!nodes[i].child) continue;
        running = !nodes[i].child->Poll() || running;
        Relay(description.nodes[i], nodes[i], false);
      }
      if (running) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  return stopped_by;
}

// Each node's exit, said; 1 when one failed (not stopped by our SIGINT).
int ReportExits(const LaunchDescription& description, std::vector<Running>& nodes,
                const std::vector<int>& stopped_by) {
  int result = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (!nodes[i].child) continue;
    Relay(description.nodes[i], nodes[i], true);
    const int code = nodes[i].child->Poll().value_or(128 + SIGKILL);
    // Ended by the SIGINT of this stop (a program without a handler): stopped
    // as asked, not failed. One that needed SIGTERM or SIGKILL did not stop.
    const bool asked = code == 128 + SIGINT && stopped_by[i] == SIGINT;
    std::string how;
    if (asked) {
      how = " (stopped by the launch's signal)";
    } else if (stopped_by[i] == SIGKILL && nodes[i].child->EndingSignal() == SIGKILL) {
      how = " (killed: it did not stop on SIGINT or SIGTERM)";
    } else if (const int signal = nodes[i].child->EndingSignal()) {
      how = " (ended by signal " + std::to_string(signal) + ")";
    }
    std::cout << "[launch] " << description.nodes[i].name << " exited with code " << code << how
              << std::endl;
    if (code != 0 && !asked) result = 1;
  }
  return result;
}

}  // namespace

int RunLaunch(const LaunchDescription& description, const LaunchRunOptions& options,
              ShutdownSignal& shutdown) {
  std::vector<Running> nodes(description.nodes.size());
  const LaunchEnd end = Supervise(description, options, shutdown, nodes);
  std::cout << "[launch] stopping all nodes (" << end.reason << ")" << std::endl;
  const auto stopped_by = StopAll(description, options, nodes);
  const int exits = ReportExits(description, nodes, stopped_by);
  return end.result != 0 ? end.result : exits;
}

}  // namespace structloc::process
