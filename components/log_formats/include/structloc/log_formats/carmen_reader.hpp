// Streams a CARMEN log (.clf/.log, plain or gzip-compressed, read through
// zlib): ODOM, FLASER/RLASER (old format), RAWLASER1-4 and ROBOTLASER1-2
// lines, plus our PARAM structloc_laser_time_increment. Other message types
// are counted and skipped. A line is used only when its field count is exactly
// what its declared beam and remission counts imply and every field parses;
// otherwise it is counted as malformed with its line number and the reason,
// never fatal, so that real logs with quirks read through. A range that is
// NaN, infinite or beyond the float range (1e400) is one invalid beam (no
// return), not a malformed line. A file that cannot be read to its end (corrupt
// or truncated .gz, a folder) is an error.
//
// FLASER beam rule (CARMEN readlog.c): beams start at -90 deg; 181 or 180
// beams -> 1 deg steps, 361 or 360 -> 0.5 deg, 401 or 400 -> 0.25 deg; any
// other count n spreads 180 deg evenly ((n - 1) steps). Ranges above the
// CARMEN max range (80 m; SICK "no return" ~81.9 m) stay as they are and are
// dropped by the localisation's range gate.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/log_formats/log_lines.hpp"

namespace structloc::log_formats {

struct CarmenRecord {
  enum class Kind { kOdometry, kScan };
  Kind kind = Kind::kOdometry;
  double stamp = 0.0;  // ipc timestamp
  size_t line = 0;
  std::string tag;  // ODOM, FLASER, ROBOTLASER1, ...
  // ODOM: the robot pose; scans: the robot (odometry) pose when the line has one.
  std::optional<geometry::Pose2D> robot_pose;
  std::optional<geometry::Pose2D> laser_pose;  // scans with a laser pose
  double linear = 0.0, angular = 0.0;          // tv, rv where given
  // Scans only.
  double start_angle = 0.0, angular_resolution = 0.0, max_range = 80.0;
  std::vector<float> ranges;
};

// Limits that keep a hostile or mistaken log from exhausting memory or time.
struct CarmenLimits {
  size_t max_beams = 100000;    // ranges (and remissions) per laser line
  size_t max_lines = 50000000;  // lines per log (about 2 days of a 50 Hz ODOM + 10 Hz laser log)
  InflateBound inflate;         // a .gz log's inflated size (16 MiB + 20 times the compressed)
  // The longest line read: 32 characters for each of 2 * max_beams values and
  // the fixed fields. Longer lines are malformed and never held in memory.
  size_t MaxLineBytes() const { return 32 * (2 * max_beams + 64); }
};

struct MalformedLine {
  size_t line = 0;
  std::string reason;  // e.g. "360 beams declared, 359 values"
};

struct CarmenStats {
  size_t lines = 0;
  size_t odometry = 0;
  size_t scans = 0;
  size_t comments = 0;
  size_t malformed = 0;
  std::vector<MalformedLine> malformed_lines;  // the first few, with their reasons
  std::map<std::string, size_t> skipped;       // other message types by name
};

class CarmenReader {
 public:
  // Throws std::runtime_error naming the file when it cannot be opened, is a
  // folder, or is named .gz without being gzip data.
  explicit CarmenReader(const std::string& path, const CarmenLimits& limits = {});

  // The next ODOM or scan record; false at the end of the file. Throws
  // std::runtime_error naming the file when it cannot be read to its end or
  // has more than limits.max_lines lines.
  bool Next(CarmenRecord& record);
  const CarmenStats& Stats() const { return stats_; }
  // From PARAM structloc_laser_time_increment, when the log has it (else 0).
  double LaserTimeIncrement() const { return time_increment_; }

 private:
  enum class ParseResult { kRecord, kSkipped, kMalformed };
  ParseResult Parse(const std::string& line, CarmenRecord& record);
  // One per message kind, on the line's fields (the tag first).
  using FieldViews = std::vector<std::string_view>;
  ParseResult ParseOdometry(const FieldViews& f, CarmenRecord& record);
  ParseResult ParseFlaser(const FieldViews& f, CarmenRecord& record);
  ParseResult ParseLaser(const FieldViews& f, bool robot_laser, CarmenRecord& record);
  ParseResult ParseParam(const FieldViews& f);
  ParseResult Skip(const std::string& tag);
  ParseResult Malformed(std::string reason);
  std::string path_;
  CarmenLimits limits_;
  LogLines lines_;
  std::string reason_;  // why the last line was malformed
  CarmenStats stats_;
  double time_increment_ = 0.0;
};

// What a reader left out, for the user: "N malformed lines of PATH left out"
// with the first few lines and their reasons, one per line; "" when none was.
std::string MalformedLinesText(const CarmenStats& stats, const std::string& path);

// FLASER angles from the beam count (the rule above).
void FlaserGeometry(size_t beams, double* start_angle, double* resolution);

}  // namespace structloc::log_formats
