// Reading scans with their poses from CARMEN logs (see header).
#include "structloc/map_building/posed_scans.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "structloc/config/strict_number.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/log_formats/carmen_reader.hpp"

namespace structloc::map_building {
namespace {

// The widest gap between two scans whose poses still give the laser's motion
// during one of them.
constexpr double kMaxMotionGapS = 0.5;

// Thesis 3.6, EQ 45: each scan's beams were measured from the laser moving
// as it moves from this scan's pose to the next's (the previous's for the
// last scan), linearly; every point is moved into the laser frame of the
// first beam (the scan's stamp and pose). Beam i was measured
// `time_increment` * i after the first.
// (The localiser's LinearBeamMotion is the same motion for a whole scan in
// its own scan type; map building does not depend on the localiser.)
size_t Deskew(std::vector<PosedScan>& scans, double time_increment) {
  size_t deskewed = 0;
  for (size_t k = 0; k < scans.size(); ++k) {
    const auto usable = [&](size_t n) {
      const double dt = std::abs(scans[n].stamp - scans[k].stamp);
      return dt > 0.0 && dt <= kMaxMotionGapS;
    };
    size_t n = k + 1;
    if (n >= scans.size() || !usable(n)) {
      if (k == 0 || !usable(k - 1)) continue;
      n = k - 1;
    }
    const geometry::Pose2D motion = geometry::Between(scans[k].laser_pose, scans[n].laser_pose);
    const double per_s = 1.0 / (scans[n].stamp - scans[k].stamp);
    for (size_t j = 0; j < scans[k].points.size(); ++j) {
      const double f = per_s * time_increment * scans[k].point_beams[j];
      const geometry::Pose2D beam{f * motion.x, f * motion.y, f * motion.theta};
      scans[k].points[j] = beam.Apply(scans[k].points[j]);
    }
    ++deskewed;
  }
  return deskewed;
}

}  // namespace

std::string DeskewText(const PosedScanLog& log) {
  if (log.deskewed == 0) return "";
  char text[160];
  std::snprintf(text, sizeof text,
                "  %zu scans de-skewed by the log's beam timing (%.4f ms between beams)\n",
                log.deskewed, 1000.0 * log.time_increment_s);
  return text;
}

PosedScanLog ReadPosedScans(const std::string& log_path, const PosedScanOptions& options,
                            ScanDeskew deskew) {
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
    const auto in_range = [&](double r) {
      return std::isfinite(r) && r >= options.min_range_m && r <= options.max_range_m &&
             r < record.max_range;
    };
    // Room for the readings kept, counted first: grown by doubling, the
    // vectors would hold up to twice what they need, for every scan of a
    // long log.
    const auto kept =
        static_cast<size_t>(std::count_if(record.ranges.begin(), record.ranges.end(), in_range));
    scan.points.reserve(kept);
    scan.ranges.reserve(kept);
    scan.point_beams.reserve(kept);
    for (size_t i = 0; i < record.ranges.size(); ++i) {
      const double r = record.ranges[i];
      ++log.readings;
      if (!in_range(r)) {
        ++log.out_of_range;
        continue;
      }
      const double a = record.start_angle + static_cast<double>(i) * record.angular_resolution;
      scan.points.emplace_back(r * std::cos(a), r * std::sin(a));
      scan.ranges.push_back(r);
      scan.point_beams.push_back(static_cast<uint32_t>(i));
    }
    log.scans.push_back(std::move(scan));
  }
  log.reader = reader.Stats();
  log.time_increment_s = reader.LaserTimeIncrement();
  if (log.time_increment_s > 0.0 && deskew == ScanDeskew::kByNeighbours)
    log.deskewed = Deskew(log.scans, log.time_increment_s);
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
