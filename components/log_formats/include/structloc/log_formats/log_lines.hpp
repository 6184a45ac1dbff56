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

// How far gzip data may inflate: a 1 MB .gz of one line repeated inflates
// to a gigabyte (the real logs inflate 4-5 times). Past `allowance_bytes`, at
// most `max_ratio` times the compressed size is read.
struct InflateBound {
  size_t allowance_bytes = 16u << 20;
  double max_ratio = 20.0;
};

class LogLines {
 public:
  // Throws std::runtime_error naming `path` when it cannot be opened, is a
  // folder, or is named *.gz without being gzip data. Files not named *.gz are
  // read as they are, or decompressed when they hold gzip data.
  LogLines(const std::string& path, size_t max_line_bytes, const InflateBound& inflate = {});
  ~LogLines();
  LogLines(const LogLines&) = delete;
  LogLines& operator=(const LogLines&) = delete;

  // The next line without its end of line; false at the end of the file.
  // `too_long` is set when the line exceeded the limit (then `line` holds only
  // its beginning). Throws std::runtime_error naming the file and the line on
  // read or decompression errors, and config::ConfigError when gzip data
  // inflate past the InflateBound.
  bool Next(std::string& line, bool& too_long);

 private:
  bool Fill();
  std::string path_;
  size_t max_line_bytes_;
  gzFile_s* file_ = nullptr;
  std::vector<char> buffer_;
  size_t begin_ = 0, end_ = 0;
  size_t lines_read_ = 0;
  size_t inflated_ = 0;      // bytes read so far
  size_t max_inflated_ = 0;  // 0: plain text, no bound
  bool at_end_ = false;
};

}  // namespace structloc::log_formats
