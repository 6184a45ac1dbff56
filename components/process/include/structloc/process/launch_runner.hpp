// Runs a launch description: starts every node as a child process (its output
// relayed line by line, prefixed "[name] " as ros2 launch does), forwards
// SIGINT/SIGTERM, starts a node with respawn="true" again (after its
// respawn_delay) whenever it ends, stops all of them when another node ends
// (non-zero, naming the node and its exit code or signal, when it died) or
// the duration ends, and reports each node's exit code. DDS-free.
#pragma once

#include <optional>

#include "structloc/process/launch_file.hpp"
#include "structloc/process/shutdown_signal.hpp"

namespace structloc::process {

struct LaunchRunOptions {
  std::optional<double> duration_s;  // stop everything after this long; none = until a signal
  double stop_grace_s = 5.0;         // SIGINT -> SIGTERM grace (all nodes together)
};

// Returns 0 when every node stopped cleanly, otherwise 1 (also when a node
// without respawn died). `shutdown` must have
// been constructed at the start of main().
int RunLaunch(const LaunchDescription& description, const LaunchRunOptions& options,
              ShutdownSignal& shutdown);

}  // namespace structloc::process
