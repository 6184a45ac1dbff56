// Output files that never lose data: written to a temporary file beside the
// target and renamed over it only when everything was written and flushed, so
// a failed run leaves an existing file untouched; refused when the target is
// one of the run's inputs (the same file by device and inode, whatever its
// name) or a symbolic link (only a link to a device or pipe, /dev/stdout, is
// written through, in place). Every file structloc writes goes through this.
// DDS-free.
#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace structloc::config {

class OutputFile {
 public:
  // Throws ConfigError when `path` is (the same file as) one of `inputs`, a
  // symbolic link to a file, or when its folder is missing or not writable.
  // Nothing is created at `path` until Commit().
  explicit OutputFile(std::string path, const std::vector<std::string>& inputs = {});
  // Removes the temporary file when Commit() was not reached.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& Stream() { return stream_; }
  const std::string& Path() const { return path_; }
  // Writes everything to disk (flush, fsync) without replacing the target yet;
  // throws std::runtime_error naming the file when a write failed (disk
  // full...). A run with several outputs flushes them all before it commits
  // any, so that a failure in one leaves every existing file untouched.
  void Flush();
  // Flush() if not done, then renames the temporary file onto the target
  // (devices and pipes such as /dev/stdout are written in place).
  void Commit();

 private:
  std::string path_;
  std::string temp_path_;
  std::ofstream stream_;
  bool flushed_ = false;
  bool committed_ = false;
};

// Throws ConfigError when `output` names the same file as one of `inputs`.
void RefuseOverwritingInput(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace structloc::config
