// The structloc CLI's subcommands; each lives in its own file and returns the
// process exit code (0 success, 1 failure, 2 usage or configuration error).
#pragma once

#include <string>

namespace structloc::cli {

struct Invocation {
  int argc;
  char** argv;          // argv[0] is "structloc", argv[1] the subcommand
  std::string bin_dir;  // folder of the structloc executable (and the components)
};

int LaunchCommand(const Invocation& invocation);
int DemoCommand(const Invocation& invocation);
int WatchCommand(const Invocation& invocation);
int SimulateCommand(const Invocation& invocation);
int RenderCommand(const Invocation& invocation);
int ReplayCommand(const Invocation& invocation);
int CalibrateCommand(const Invocation& invocation);
int ParamsCommand(const Invocation& invocation);
int TopicsCommand(const Invocation& invocation);
int MapCommand(const Invocation& invocation);
int SynthesiseOdometryCommand(const Invocation& invocation);
int RecordCommand(const Invocation& invocation);
int SlamCommand(const Invocation& invocation);

}  // namespace structloc::cli
