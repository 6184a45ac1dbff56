// Reads a text log line by line, plain or gzip-compressed, through zlib (no
// shell, no external gzip): any file name opens, and a read or decompression
// failure (corrupt or truncated .gz, a folder, an I/O error) is an error naming
// the file instead of a silently shorter log. Lines longer than a limit are
// reported as such without being held in memory. DDS-free.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

struct gzFile_s;  // zlib's file handle, kept out of this header

namespace structloc::log_formats {

class LogLines {
 public:
  // Throws std::runtime_error naming `path` when it cannot be opened, is a
  // folder, or is named *.gz without being gzip data. Files not named *.gz are
  // read as they are, or decompressed when they hold gzip data.
  LogLines(const std::string& path, size_t max_line_bytes);
  ~LogLines();
  LogLines(const LogLines&) = delete;
  LogLines& operator=(const LogLines&) = delete;

  // The next line without its end of line; false at the end of the file.
  // `too_long` is set when the line exceeded the limit (then `line` holds only
  // its beginning). Throws std::runtime_error naming the file and the line on
  // read or decompression errors.
  bool Next(std::string& line, bool& too_long);

 private:
  bool Fill();
  std::string path_;
  size_t max_line_bytes_;
  gzFile_s* file_ = nullptr;
  std::vector<char> buffer_;
  size_t begin_ = 0, end_ = 0;
  size_t lines_read_ = 0;
  bool at_end_ = false;
};

}  // namespace structloc::log_formats
