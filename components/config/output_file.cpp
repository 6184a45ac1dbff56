// OutputFile (see header).
#include "structloc/config/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <stdexcept>

#include "structloc/config/strict_xml.hpp"

namespace structloc::config {
namespace {

// A new file beside `target` under a random name, created with mode 0666 so
// that the kernel applies the umask, as for any new file (mkstemp makes it
// 0600, and reading the umask would race the process's other threads).
int CreateTemporary(const std::string& target, std::string* path) {
  std::random_device random;
  for (int attempt = 0; attempt < 100; ++attempt) {
    char suffix[24];
    std::snprintf(suffix, sizeof(suffix), ".tmp.%08x", static_cast<unsigned>(random()));
    *path = target + suffix;
    const int fd = ::open(path->c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  return -1;
}

}  // namespace

void RefuseOverwritingInput(const std::string& output, const std::vector<std::string>& inputs) {
  for (const auto& input : inputs) {
    std::error_code error;
    if (input.empty()) continue;
    if (output == input || std::filesystem::equivalent(output, input, error)) {
      throw ConfigError(output + ": refusing to write the output over the input " + input);
    }
  }
}

OutputFile::OutputFile(std::string path, const std::vector<std::string>& inputs)
    : path_(std::move(path)) {
  if (path_.empty()) throw ConfigError("an output file name is empty");
  RefuseOverwritingInput(path_, inputs);
  std::error_code error;
  if (std::filesystem::is_directory(path_, error)) {
    throw ConfigError(path_ + ": is a folder, not a file");
  }
  const auto status = std::filesystem::status(path_, error);
  // A symbolic link is not followed: replacing the file it names would write
  // wherever whoever made the link chose (another user's file, for a name in
  // /tmp). Only a link to a device or pipe (/dev/stdout) is written through.
  if (std::filesystem::is_symlink(path_, error) &&
      (!std::filesystem::exists(status) || std::filesystem::is_regular_file(status))) {
    throw ConfigError(path_ +
                      ": is a symbolic link; outputs are not written through links (name the "
                      "file itself, or remove the link)");
  }
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    // A device or pipe (/dev/stdout, a FIFO): written in place, errors still checked.
    stream_.open(path_, std::ios::binary);
    if (!stream_) throw ConfigError(path_ + ": cannot open it for writing");
    return;
  }
  const int fd = CreateTemporary(path_, &temp_path_);
  if (fd < 0) {
    throw ConfigError(path_ + ": cannot create an output file there (" +
                      std::string(std::strerror(errno)) + ")");
  }
  ::close(fd);
  stream_.open(temp_path_, std::ios::binary | std::ios::trunc);
  if (!stream_) {
    std::remove(temp_path_.c_str());
    throw ConfigError(path_ + ": cannot write an output file there");
  }
}

OutputFile::~OutputFile() {
  if (committed_) return;
  stream_.close();
  if (!temp_path_.empty()) std::remove(temp_path_.c_str());
}

void OutputFile::Flush() {
  if (flushed_) return;
  flushed_ = true;
  stream_.flush();
  const bool written = static_cast<bool>(stream_);
  stream_.close();
  bool synced = written && !stream_.fail();
  if (synced && !temp_path_.empty()) {
    const int fd = ::open(temp_path_.c_str(), O_RDONLY);
    synced = fd >= 0 && ::fsync(fd) == 0;
    if (fd >= 0) ::close(fd);
  }
  if (!synced) {
    const std::string reason = errno != 0 ? std::strerror(errno) : "stream error";
    if (!temp_path_.empty()) std::remove(temp_path_.c_str());
    committed_ = true;
    throw std::runtime_error(path_ + ": writing failed (" + reason +
                             "); the previous file, if any, is unchanged");
  }
}

void OutputFile::Commit() {
  Flush();
  if (committed_) return;
  committed_ = true;
  if (temp_path_.empty()) return;
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temp_path_.c_str());
    throw std::runtime_error(path_ + ": cannot replace the file (" + reason + ")");
  }
}

}  // namespace structloc::config
