// Names the CLI derives from input paths: a file's name for messages and
// comments, and its stem (without ".gz" and the format's extension) as the
// default name of a map made from it.
#pragma once

#include <string>

namespace structloc::cli {

inline std::string FileName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// "logs/intel-corrected.log.gz" -> "intel-corrected"; `fallback` when nothing is left.
inline std::string Stem(const std::string& path, const std::string& fallback) {
  std::string name = FileName(path);
  if (name.size() > 3 && name.compare(name.size() - 3, 3, ".gz") == 0) name.resize(name.size() - 3);
  const auto dot = name.find_last_of('.');
  if (dot != std::string::npos && dot > 0) name.resize(dot);
  return name.empty() ? fallback : name;
}

}  // namespace structloc::cli
