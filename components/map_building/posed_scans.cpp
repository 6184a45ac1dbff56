// Reading scans with their poses from CARMEN logs (see header).
#include "structloc/map_building/posed_scans.hpp"

#include <cmath>

#include "structloc/config/strict_xml.hpp"
#include "structloc/log_formats/carmen_reader.hpp"

namespace structloc::map_building {

PosedScanLog ReadPosedScans(const std::string& log_path, const PosedScanOptions& options) {
  log_formats::CarmenReader reader(log_path);
  log_formats::CarmenRecord record;
  PosedScanLog log;
  while (reader.Next(record)) {
    if (record.kind != log_formats::CarmenRecord::Kind::kScan) continue;
    const auto& pose = record.laser_pose ? record.laser_pose : record.robot_pose;
    if (!pose || !geometry::IsFinite(*pose)) {
      ++log.scans_without_pose;
      continue;
    }
    PosedScan scan;
    scan.index = log.scans.size();
    scan.line = record.line;
    scan.laser_pose = *pose;
    scan.angular_resolution = record.angular_resolution;
    scan.points.reserve(record.ranges.size());
    for (size_t i = 0; i < record.ranges.size(); ++i) {
      const double r = record.ranges[i];
      ++log.readings;
      if (!std::isfinite(r) || r < options.min_range_m || r > options.max_range_m ||
          r >= record.max_range) {
        ++log.out_of_range;
        continue;
      }
      const double a = record.start_angle + static_cast<double>(i) * record.angular_resolution;
      scan.points.emplace_back(r * std::cos(a), r * std::sin(a));
      scan.ranges.push_back(r);
    }
    log.scans.push_back(std::move(scan));
  }
  log.malformed_lines = reader.Stats().malformed;
  if (log.scans.empty()) {
    throw config::ConfigError(log_path + ": no laser scan with a pose (FLASER, ROBOTLASER) in " +
                              std::to_string(reader.Stats().lines) + " lines");
  }
  return log;
}

}  // namespace structloc::map_building
