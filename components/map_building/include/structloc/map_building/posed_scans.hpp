// The input of the map makers that learn from recordings: every laser scan of
// a CARMEN log with the pose of the laser when it was taken. In SLAM-corrected
// logs (the Radish/GMapping "-corrected" logs) that pose is the SLAM estimate,
// so the scans line up in the map frame. DDS-free.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/log_formats/carmen_reader.hpp"

namespace structloc::map_building {

struct PosedScanOptions {
  double min_range_m = 0.05;  // closer readings are the robot itself or dust
  double max_range_m = 20.0;  // farther ones are too sparse and too noisy in angle to map walls;
                              // SICK "no return" readings (80+ m) are always dropped
};

struct PosedScan {
  size_t index = 0;             // scan number in the log, from 0
  size_t line = 0;              // line in the log
  double stamp = 0.0;           // the line's (ipc) timestamp
  geometry::Pose2D laser_pose;  // map frame
  // The robot's pose in the same frame, when the line gives it too (with the
  // laser pose it gives the mounting).
  std::optional<geometry::Pose2D> robot_pose;
  // Readings within the range limits, in beam order, in the laser frame, with
  // the range of each (a jump in range separates objects).
  std::vector<Eigen::Vector2d> points;
  std::vector<double> ranges;
  std::vector<uint32_t> point_beams;  // the beam of each point (its time: beam x time increment)
  double angular_resolution = 0.0;    // rad between beams
  size_t beams = 0;                   // readings of the scan, within the limits or not
};

struct PosedScanLog {
  std::vector<PosedScan> scans;
  size_t readings = 0;              // all readings of all scans
  size_t out_of_range = 0;          // of them, dropped by the range limits
  log_formats::CarmenStats reader;  // the lines read, and those left out as malformed
  size_t scans_without_pose = 0;    // laser lines with no pose at all (raw RAWLASER lines)
  // Where the log gives its laser's beam timing (structloc's recordings do),
  // the time between beams, and the scans de-skewed with it (moved into the
  // first beam's laser frame by the motion to the neighbouring scan's pose).
  double time_increment_s = 0.0;
  size_t deskewed = 0;
};

// Whether ReadPosedScans de-skews the scans where the log gives its beam
// timing: by the motion to the neighbouring scan's pose, or not (for a reader
// that de-skews them itself, e.g. once it knows when each scan was taken).
enum class ScanDeskew { kByNeighbours, kNone };

// Reads every scan of the log with its laser pose (the line's laser pose, else
// the robot pose: the corrected logs have no laser offset), de-skewed where
// the log gives its beam timing (thesis 3.6, EQ 45) unless told not to. Throws
// std::runtime_error naming the file when it cannot be read, and
// config::ConfigError when it holds no scan with a pose.
PosedScanLog ReadPosedScans(const std::string& log_path, const PosedScanOptions& options,
                            ScanDeskew deskew = ScanDeskew::kByNeighbours);

// "  N scans de-skewed by the log's beam timing (... ms between beams)\n", or
// "" where the log gives none: for the commands that read posed scans.
std::string DeskewText(const PosedScanLog& log);

// Keeps the scans numbered first .. last - 1 (their `index`), so that a map can
// be built from one part of a recording and checked or localised on another;
// the reading counts are then those of the kept scans.
// Throws config::ConfigError when the range is empty or starts beyond the log.
void KeepScans(PosedScanLog& log, size_t first, size_t last);

// "A:B" (either side may be empty: from the start, to the end) as [first, last);
// throws config::ConfigError naming `text` otherwise.
std::pair<size_t, size_t> ParseScanRange(const std::string& text);

}  // namespace structloc::map_building
