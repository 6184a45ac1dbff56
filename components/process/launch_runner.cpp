// Launch runner (see header).
#include "structloc/process/launch_runner.hpp"

#include <iostream>
#include <memory>

#include "structloc/process/child_process.hpp"

namespace structloc::process {

int RunLaunch(const LaunchDescription& description, const LaunchRunOptions& options,
              ShutdownSignal& shutdown) {
  std::vector<std::unique_ptr<ChildProcess>> children;
  for (const auto& node : description.nodes) {
    std::cout << "[launch] starting " << node.name << ": " << node.executable;
    for (const auto& a : node.arguments) std::cout << " " << a;
    std::cout << std::endl;
    children.push_back(std::make_unique<ChildProcess>(node.executable, node.arguments,
                                                      ChildProcess::Output::kInherit));
    std::cout << "[launch] " << node.name << " has pid " << children.back()->Pid() << std::endl;
  }
  const auto start = std::chrono::steady_clock::now();
  std::string reason = "stop signal";
  while (!shutdown.WaitFor(std::chrono::milliseconds(50))) {
    bool one_ended = false;
    for (size_t i = 0; i < children.size(); ++i) {
      if (auto code = children[i]->Poll()) {
        reason = description.nodes[i].name + " exited with code " + std::to_string(*code);
        one_ended = true;
      }
    }
    if (one_ended) break;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (options.duration_s && elapsed >= *options.duration_s) {
      reason = "duration of " + std::to_string(*options.duration_s) + " s reached";
      break;
    }
  }
  std::cout << "[launch] stopping all nodes (" << reason << ")" << std::endl;
  int result = 0;
  const auto grace = std::chrono::milliseconds(static_cast<long>(options.stop_grace_s * 1000));
  for (size_t i = 0; i < children.size(); ++i) {
    const int code = children[i]->Stop(grace);
    std::cout << "[launch] " << description.nodes[i].name << " exited with code " << code
              << std::endl;
    if (code != 0) result = 1;
  }
  return result;
}

}  // namespace structloc::process
