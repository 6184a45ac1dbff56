// Streams a CARMEN log (.clf/.log, optionally .gz through `gzip -dc`): ODOM,
// FLASER/RLASER (old format), RAWLASER1-4 and ROBOTLASER1-2 lines, plus our
// PARAM structloc_laser_time_increment. Other message types are counted and
// skipped; malformed lines are counted with their first line numbers, never
// fatal, so that real logs with quirks read through.
//
// FLASER beam rule (CARMEN readlog.c): beams start at -90 deg; 181 or 180
// beams -> 1 deg steps, 361 or 360 -> 0.5 deg, 401 or 400 -> 0.25 deg; any
// other count n spreads 180 deg evenly ((n - 1) steps). Ranges above the
// CARMEN max range (80 m; SICK "no return" ~81.9 m) stay as they are and are
// dropped by the localisation's range gate.
#pragma once

#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pose2d.hpp"

namespace structloc::logs {

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

struct CarmenStats {
  size_t lines = 0;
  size_t odometry = 0;
  size_t scans = 0;
  size_t comments = 0;
  size_t malformed = 0;
  std::vector<size_t> malformed_lines;    // the first few
  std::map<std::string, size_t> skipped;  // other message types by name
};

class CarmenReader {
 public:
  // Throws std::runtime_error when the file cannot be opened.
  explicit CarmenReader(const std::string& path);
  ~CarmenReader();
  CarmenReader(const CarmenReader&) = delete;
  CarmenReader& operator=(const CarmenReader&) = delete;

  // The next ODOM or scan record; false at the end of the file.
  bool Next(CarmenRecord& record);
  const CarmenStats& Stats() const { return stats_; }
  // From PARAM structloc_laser_time_increment, when the log has it (else 0).
  double LaserTimeIncrement() const { return time_increment_; }

 private:
  enum class ParseResult { kRecord, kSkipped, kMalformed };
  ParseResult Parse(const std::string& line, CarmenRecord& record);
  FILE* file_ = nullptr;
  bool pipe_ = false;
  std::string path_;
  CarmenStats stats_;
  double time_increment_ = 0.0;
};

// FLASER angles from the beam count (the rule above).
void FlaserGeometry(size_t beams, double* start_angle, double* resolution);

}  // namespace structloc::logs
