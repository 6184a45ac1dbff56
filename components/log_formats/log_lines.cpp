// LogLines (see header).
#include "structloc/log_formats/log_lines.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "structloc/config/strict_xml.hpp"

namespace structloc::log_formats {
namespace {

constexpr size_t kChunkBytes = 1 << 16;

bool NamedGz(const std::string& path) {
  return path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0;
}

}  // namespace

LogLines::LogLines(const std::string& path, size_t max_line_bytes, const InflateBound& inflate)
    : path_(path), max_line_bytes_(max_line_bytes), buffer_(kChunkBytes) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw std::runtime_error(path + ": is a folder, not a log file");
  }
  file_ = gzopen(path.c_str(), "rb");
  if (file_ == nullptr) {
    throw std::runtime_error(path + ": cannot open the log (" + std::strerror(errno) + ")");
  }
  gzbuffer(file_, 4 * kChunkBytes);
  if (NamedGz(path) && gzdirect(file_) != 0) {
    gzclose(file_);
    file_ = nullptr;
    throw std::runtime_error(path +
                             ": not gzip data although the name ends in .gz; a plain-text log "
                             "must not be named .gz");
  }
  if (gzdirect(file_) == 0) {
    const auto compressed = std::filesystem::file_size(path, error);
    max_inflated_ =
        inflate.allowance_bytes +
        static_cast<size_t>(inflate.max_ratio * static_cast<double>(error ? 0 : compressed));
  }
}

LogLines::~LogLines() {
  if (file_ != nullptr) gzclose(file_);
}

bool LogLines::Fill() {
  if (at_end_) return false;
  const int got = gzread(file_, buffer_.data(), static_cast<unsigned>(buffer_.size()));
  int code = Z_OK;
  const char* message = gzerror(file_, &code);
  if (got < 0 || code != Z_OK) {
    throw std::runtime_error(path_ + ": cannot read past line " + std::to_string(lines_read_) +
                             " (" + message +
                             "): the log is corrupt or truncated; check it with gzip -t");
  }
  if (got == 0) {
    at_end_ = true;
    return false;
  }
  inflated_ += static_cast<size_t>(got);
  if (max_inflated_ > 0 && inflated_ > max_inflated_) {
    throw config::ConfigError(path_ + ": the gzip data inflate to more than " +
                              std::to_string(max_inflated_) + " bytes by line " +
                              std::to_string(lines_read_) +
                              ", far more than a log compresses (a gzip bomb?)");
  }
  begin_ = 0;
  end_ = static_cast<size_t>(got);
  return true;
}

bool LogLines::Next(std::string& line, bool& too_long) {
  line.clear();
  too_long = false;
  bool started = false;
  while (begin_ < end_ || Fill()) {
    started = true;
    const char* start = buffer_.data() + begin_;
    const size_t available = end_ - begin_;
    const auto* newline = static_cast<const char*>(std::memchr(start, '\n', available));
    const size_t length = newline != nullptr ? static_cast<size_t>(newline - start) : available;
    const size_t room = max_line_bytes_ > line.size() ? max_line_bytes_ - line.size() : 0;
    if (length > room) too_long = true;
    line.append(start, std::min(length, room));
    begin_ += length + (newline != nullptr ? 1 : 0);
    if (newline != nullptr) {
      ++lines_read_;
      return true;
    }
  }
  if (started) ++lines_read_;
  return started;
}

}  // namespace structloc::log_formats
