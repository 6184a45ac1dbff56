// Reading scans with their poses from CARMEN logs (see header).
#include "structloc/map_building/posed_scans.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "structloc/config/strict_number.hpp"
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
    scan.stamp = record.stamp;
    scan.laser_pose = *pose;
    if (record.laser_pose && record.robot_pose && geometry::IsFinite(*record.robot_pose))
      scan.robot_pose = record.robot_pose;
    scan.angular_resolution = record.angular_resolution;
    scan.beams = record.ranges.size();
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
  log.reader = reader.Stats();
  if (log.scans.empty()) {
    throw config::ConfigError(log_path + ": no laser scan with a pose (FLASER, ROBOTLASER) in " +
                              std::to_string(reader.Stats().lines) + " lines");
  }
  return log;
}

void KeepScans(PosedScanLog& log, size_t first, size_t last) {
  const size_t total = log.scans.size();
  if (first >= last || first >= total) {
    throw config::ConfigError("the scans " + std::to_string(first) + ":" +
                              (last == SIZE_MAX ? std::string() : std::to_string(last)) +
                              " hold none of the log's " + std::to_string(total) + " scans");
  }
  log.scans.erase(log.scans.begin() + static_cast<long>(std::min(last, total)), log.scans.end());
  log.scans.erase(log.scans.begin(), log.scans.begin() + static_cast<long>(first));
  log.readings = 0;
  log.out_of_range = 0;
  for (const auto& scan : log.scans) {
    log.readings += scan.beams;
    log.out_of_range += scan.beams - scan.points.size();
  }
}

std::pair<size_t, size_t> ParseScanRange(const std::string& text) {
  const auto colon = text.find(':');
  const auto bad = [&text] {
    return config::ConfigError(
        "--scans must be FIRST:LAST (scan numbers from 0, LAST not "
        "included, either may be left out), not '" +
        text + "'");
  };
  if (colon == std::string::npos) throw bad();
  const auto number = [&bad](const std::string& part, size_t fallback) {
    if (part.empty()) return fallback;
    const auto value = config::ParseInteger(part);
    if (!value || *value < 0) throw bad();
    return static_cast<size_t>(*value);
  };
  return {number(text.substr(0, colon), 0), number(text.substr(colon + 1), SIZE_MAX)};
}

}  // namespace structloc::map_building
