// Run-time lookup of the executable's folder and the shared data (see header).
#include "structloc/config/install_layout.hpp"

#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "structloc/config/strict_xml.hpp"

namespace structloc::config {

std::string ExecutableDirectory() {
  char path[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", path, sizeof(path) - 1);
  if (n <= 0) throw ConfigError("cannot find the running executable: /proc/self/exe unreadable");
  path[n] = '\0';
  return std::filesystem::path(path).parent_path().string();
}

std::string ShareDirectory() {
  const char* env = std::getenv("STRUCTLOC_SHARE_DIR");
  const bool from_env = env != nullptr && *env != '\0';
  const std::filesystem::path dir =
      from_env ? std::filesystem::path(env)
               : std::filesystem::path(ExecutableDirectory()) / ".." / "share" / "structloc";
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error)) {
    throw ConfigError("structloc's data folder " + dir.string() + " does not exist (" +
                      (from_env ? std::string("set by STRUCTLOC_SHARE_DIR")
                                : std::string("beside the executable; install with "
                                              "\"cmake --install\" or set STRUCTLOC_SHARE_DIR")) +
                      ")");
  }
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(dir, error);
  return error ? dir.string() : canonical.string();
}

std::string SharePath(const std::string& relative) {
  return ShareDirectory() + "/" + relative;
}

}  // namespace structloc::config
