// Where structloc's executables and shipped data files (maps, scenarios,
// parameters, QoS profiles, launch files) are found at run time, so that the
// same binaries work in a build tree and after "cmake --install" to any prefix:
// the data live in <executable's folder>/../share/structloc in both (the build
// tree links them there at configure time). STRUCTLOC_SHARE_DIR in the
// environment overrides the lookup.
#pragma once

#include <string>

namespace structloc::config {

// The folder holding the running executable (from /proc/self/exe).
// Throws ConfigError when the kernel does not say.
std::string ExecutableDirectory();

// The share folder: $STRUCTLOC_SHARE_DIR when set, else
// <ExecutableDirectory()>/../share/structloc. Throws ConfigError naming the
// folder looked at when it is missing.
std::string ShareDirectory();

// ShareDirectory() + "/" + relative, e.g. SharePath("qos/structloc_qos.xml").
std::string SharePath(const std::string& relative);

}  // namespace structloc::config
