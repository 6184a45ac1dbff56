// CARMEN log reader (see header).
#include "structloc/log_formats/carmen_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "structloc/log_formats/log_fields.hpp"

namespace structloc::log_formats {

void FlaserGeometry(size_t n, double* start, double* res) {
  const double deg = geometry::kPi / 180.0;
  *start = -geometry::kPi / 2;
  if (n == 181 || n == 180) {
    *res = 1.0 * deg;
  } else if (n == 361 || n == 360) {
    *res = 0.5 * deg;
  } else if (n == 401 || n == 400) {
    *res = 0.25 * deg;
  } else {
    *res = n > 1 ? geometry::kPi / static_cast<double>(n - 1) : 0.0;
  }
}

namespace {

using Fields = std::vector<std::string_view>;

// Fields after the ranges and remissions: ipc_timestamp hostname logger_timestamp,
// preceded on ROBOTLASER lines by the laser and robot poses, tv, rv,
// forward_safety_dist, side_safety_dist and turn_axis.
constexpr size_t kStampFields = 3;
constexpr size_t kRobotLaserTail = 11 + kStampFields;
constexpr size_t kFlaserTail = 6 + kStampFields;
constexpr size_t kOdomFields = 9;
// ROBOTLASER/RAWLASER: tag, laser_type, start_angle, fov, angular_res, max_range,
// accuracy, remission_mode, num_readings.
constexpr size_t kLaserHeader = 9;
constexpr double kMaxTimeIncrementS = 1.0;

bool IsMessageName(std::string_view tag) {
  if (tag.empty() || tag.size() > 64 || !std::isalpha(static_cast<unsigned char>(tag[0]))) {
    return false;
  }
  return std::all_of(tag.begin(), tag.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
  });
}

// A token as it may be shown to a user: short, and never raw binary.
std::string Quote(std::string_view token) {
  const bool printable = std::all_of(token.begin(), token.end(), [](char c) {
    return std::isprint(static_cast<unsigned char>(c)) != 0;
  });
  if (!printable) return "(non-text bytes)";
  if (token.size() > 24) return "'" + std::string(token.substr(0, 24)) + "...'";
  return "'" + std::string(token) + "'";
}

// Typed access to the fields of one line; the first problem is kept in `reason`.
class FieldReader {
 public:
  explicit FieldReader(const Fields& fields) : f_(fields) {}

  bool Finite(size_t i, const char* name, double* out) {
    const auto v = ParseFinite(f_[i]);
    if (!v) return Fail(std::string(name) + " " + Quote(f_[i]) + " is not a finite number");
    *out = *v;
    return true;
  }
  bool Pose(size_t i, const char* name, geometry::Pose2D* out) {
    const std::string n(name);
    return Finite(i, (n + " x").c_str(), &out->x) && Finite(i + 1, (n + " y").c_str(), &out->y) &&
           Finite(i + 2, (n + " theta").c_str(), &out->theta);
  }
  bool Integer(size_t i, const char* name, int64_t* out) {
    const auto v = ParseInteger(f_[i]);
    if (!v) return Fail(std::string(name) + " " + Quote(f_[i]) + " is not an integer");
    *out = *v;
    return true;
  }
  bool Count(size_t i, const char* name, uint64_t* out) {
    const auto v = ParseCount(f_[i]);
    if (!v) return Fail(std::string(name) + " " + Quote(f_[i]) + " is not a non-negative integer");
    *out = *v;
    return true;
  }
  // Ranges: a value that is NaN, infinite or beyond the float range is a beam
  // without a return (+inf), which the localisation's range gate drops.
  bool Ranges(size_t i, size_t n, std::vector<float>* out) {
    out->resize(n);
    for (size_t k = 0; k < n; ++k) {
      const auto v = ParseReal(f_[i + k]);
      if (!v) {
        return Fail("range " + std::to_string(k + 1) + " of " + std::to_string(n) + " " +
                    Quote(f_[i + k]) + " is not a number");
      }
      const bool representable =
          std::isfinite(*v) && std::abs(*v) <= std::numeric_limits<float>::max();
      (*out)[k] = representable ? static_cast<float>(*v) : std::numeric_limits<float>::infinity();
    }
    return true;
  }
  // Remissions are not used, but must still be numbers.
  bool Numbers(size_t i, size_t n, const char* name) {
    for (size_t k = 0; k < n; ++k) {
      if (!ParseReal(f_[i + k])) {
        return Fail(std::string(name) + " " + std::to_string(k + 1) + " of " + std::to_string(n) +
                    " " + Quote(f_[i + k]) + " is not a number");
      }
    }
    return true;
  }
  bool Fail(std::string why) {
    reason = std::move(why);
    return false;
  }
  std::string reason;

 private:
  const Fields& f_;
};

std::string BeamsVersusValues(uint64_t declared, size_t present) {
  return std::to_string(declared) + " beams declared, " + std::to_string(present) + " values";
}

std::string OverLimit(uint64_t n, const char* what, size_t limit) {
  return std::to_string(n) + " " + what + ", more than the limit of " + std::to_string(limit) +
         " (raise it with --max-beams)";
}

// Why a RAWLASER/ROBOTLASER line's counts do not match its field count: the
// values actually present when the remission count that follows them is 0 or
// equal to the beam count (CARMEN's two usual layouts), else what is wrong with
// the declared remission count.
std::string LaserCountMismatch(const Fields& f, uint64_t declared, size_t tail) {
  const size_t total = f.size();
  const size_t region = total - kLaserHeader - tail;  // ranges, remission count, remissions
  for (const size_t values : {region - 1, (region - 1) / 2}) {
    const auto m = ParseCount(f[kLaserHeader + values]);
    if (m && values + 1 + *m == region) return BeamsVersusValues(declared, values);
  }
  const size_t remissions_at = kLaserHeader + declared;
  if (remissions_at >= total) {
    return std::to_string(declared) + " beams declared, but the line has only " +
           std::to_string(total) + " fields";
  }
  const auto m = ParseCount(f[remissions_at]);
  if (!m) {
    return "num_remissions " + Quote(f[remissions_at]) + " after the " + std::to_string(declared) +
           " declared beams is not a non-negative integer";
  }
  return std::to_string(declared) + " beams and " + std::to_string(*m) +
         " remissions declared, but the line has " + std::to_string(total) + " fields, not " +
         std::to_string(kLaserHeader + declared + 1 + *m + tail);
}

}  // namespace

CarmenReader::CarmenReader(const std::string& path, const CarmenLimits& limits)
    : path_(path), limits_(limits), lines_(path, limits.MaxLineBytes(), limits.inflate) {}

CarmenReader::ParseResult CarmenReader::Malformed(std::string reason) {
  reason_ = std::move(reason);
  return ParseResult::kMalformed;
}

CarmenReader::ParseResult CarmenReader::Parse(const std::string& text, CarmenRecord& r) {
  const Fields f = SplitFields(text);
  const std::string_view tag = f.front();
  r = CarmenRecord{};
  r.line = stats_.lines;
  if (!IsMessageName(tag)) {
    return Malformed("not a CARMEN message (the line does not start with a message name)");
  }
  r.tag = std::string(tag);
  if (tag == "ODOM") return ParseOdometry(f, r);
  if (tag == "FLASER" || tag == "RLASER") return ParseFlaser(f, r);
  const bool robot_laser = tag.rfind("ROBOTLASER", 0) == 0;
  if (robot_laser || tag.rfind("RAWLASER", 0) == 0) return ParseLaser(f, robot_laser, r);
  if (tag == "PARAM") return ParseParam(f);
  return Skip(r.tag);
}

CarmenReader::ParseResult CarmenReader::ParseOdometry(const Fields& f, CarmenRecord& r) {
  if (f.size() != 1 + kOdomFields) {
    return Malformed(
        "ODOM needs 9 fields (x y theta tv rv accel ipc_timestamp hostname "
        "logger_timestamp), found " +
        std::to_string(f.size() - 1));
  }
  FieldReader in(f);
  geometry::Pose2D p;
  double accel;
  if (!in.Pose(1, "pose", &p) || !in.Finite(4, "tv", &r.linear) ||
      !in.Finite(5, "rv", &r.angular) || !in.Finite(6, "accel", &accel) ||
      !in.Finite(7, "ipc_timestamp", &r.stamp)) {
    return Malformed(in.reason);
  }
  r.kind = CarmenRecord::Kind::kOdometry;
  r.robot_pose = p;
  return ParseResult::kRecord;
}

CarmenReader::ParseResult CarmenReader::ParseFlaser(const Fields& f, CarmenRecord& r) {
  FieldReader in(f);
  uint64_t n = 0;
  if (f.size() < 2 || !in.Count(1, "beam count", &n)) {
    return Malformed(f.size() < 2 ? "no beam count" : in.reason);
  }
  if (n > limits_.max_beams) return Malformed(OverLimit(n, "beams", limits_.max_beams));
  const size_t fixed = 2 + kFlaserTail;
  if (f.size() != fixed + n) {
    if (f.size() < fixed) {
      return Malformed(std::to_string(n) + " beams declared, so " + std::to_string(fixed + n) +
                       " fields expected; found " + std::to_string(f.size()));
    }
    return Malformed(BeamsVersusValues(n, f.size() - fixed));
  }
  geometry::Pose2D laser, robot;
  if (!in.Ranges(2, n, &r.ranges) || !in.Pose(2 + n, "laser", &laser) ||
      !in.Pose(5 + n, "odometry", &robot) || !in.Finite(8 + n, "ipc_timestamp", &r.stamp)) {
    return Malformed(in.reason);
  }
  FlaserGeometry(n, &r.start_angle, &r.angular_resolution);
  r.kind = CarmenRecord::Kind::kScan;
  r.laser_pose = laser;
  r.robot_pose = robot;
  return ParseResult::kRecord;
}

CarmenReader::ParseResult CarmenReader::ParseLaser(const Fields& f, bool robot_laser,
                                                   CarmenRecord& r) {
  const size_t tail = robot_laser ? kRobotLaserTail : kStampFields;
  if (f.size() < kLaserHeader + 1 + tail) {
    return Malformed("too few fields for " + r.tag + ": " + std::to_string(f.size()) +
                     " (at least " + std::to_string(kLaserHeader + 1 + tail) + ")");
  }
  FieldReader in(f);
  int64_t type, remission_mode;
  double fov, accuracy;
  uint64_t n = 0, m = 0;
  if (!in.Integer(1, "laser_type", &type) || !in.Finite(2, "start_angle", &r.start_angle) ||
      !in.Finite(3, "fov", &fov) || !in.Finite(4, "angular_resolution", &r.angular_resolution) ||
      !in.Finite(5, "maximum_range", &r.max_range) || !in.Finite(6, "accuracy", &accuracy) ||
      !in.Integer(7, "remission_mode", &remission_mode) || !in.Count(8, "num_readings", &n)) {
    return Malformed(in.reason);
  }
  if (n > limits_.max_beams) return Malformed(OverLimit(n, "beams", limits_.max_beams));
  // Every beam's angle start + i * res must be a direction: a resolution of
  // 1e308 is finite but its later beams' angles are not.
  constexpr double kTurn = 2.0 * M_PI + 1e-6;
  if (!(std::abs(r.start_angle) <= kTurn) ||
      !(std::abs(r.angular_resolution) * static_cast<double>(n > 0 ? n - 1 : 0) <= kTurn)) {
    return Malformed("start_angle " + Quote(f[2]) + " and angular_resolution " + Quote(f[4]) +
                     " over " + std::to_string(n) +
                     " beams do not lie within one turn (|angle| <= 2 pi)");
  }
  const size_t remissions_at = kLaserHeader + n;  // the num_remissions field
  const auto declared_m =
      remissions_at < f.size() ? ParseCount(f[remissions_at]) : std::optional<uint64_t>();
  if (!declared_m || *declared_m > f.size() || remissions_at + 1 + *declared_m + tail != f.size()) {
    return Malformed(LaserCountMismatch(f, n, tail));
  }
  m = *declared_m;
  if (m > limits_.max_beams) return Malformed(OverLimit(m, "remissions", limits_.max_beams));
  if (!in.Ranges(kLaserHeader, n, &r.ranges) || !in.Numbers(remissions_at + 1, m, "remission")) {
    return Malformed(in.reason);
  }
  size_t next = remissions_at + 1 + m;
  if (robot_laser) {
    geometry::Pose2D laser, robot;
    double fsd, ssd, turn;
    if (!in.Pose(next, "laser", &laser) || !in.Pose(next + 3, "robot", &robot) ||
        !in.Finite(next + 6, "tv", &r.linear) || !in.Finite(next + 7, "rv", &r.angular) ||
        !in.Finite(next + 8, "forward_safety_dist", &fsd) ||
        !in.Finite(next + 9, "side_safety_dist", &ssd) ||
        !in.Finite(next + 10, "turn_axis", &turn)) {
      return Malformed(in.reason);
    }
    r.laser_pose = laser;
    r.robot_pose = robot;
    next += 11;
  }
  if (!in.Finite(next, "ipc_timestamp", &r.stamp)) return Malformed(in.reason);
  r.kind = CarmenRecord::Kind::kScan;
  return ParseResult::kRecord;
}

CarmenReader::ParseResult CarmenReader::ParseParam(const Fields& f) {
  if (f.size() >= 3 && f[1] == "structloc_laser_time_increment") {
    const auto value = ParseFinite(f[2]);
    if (!value || *value < 0.0 || *value > kMaxTimeIncrementS) {
      return Malformed("structloc_laser_time_increment " + Quote(f[2]) +
                       " is not a time between 0 and 1 s");
    }
    time_increment_ = *value;
  }
  ++stats_.skipped["PARAM"];
  return ParseResult::kSkipped;
}

CarmenReader::ParseResult CarmenReader::Skip(const std::string& tag) {
  // Counted by name for the first few kinds only: a log of endless made-up
  // tags must not grow this map without bound.
  constexpr size_t kMaxSkippedKinds = 32;
  if (stats_.skipped.count(tag) != 0 || stats_.skipped.size() < kMaxSkippedKinds) {
    ++stats_.skipped[tag];
  } else {
    ++stats_.skipped["(other kinds)"];
  }
  return ParseResult::kSkipped;
}

bool CarmenReader::Next(CarmenRecord& record) {
  std::string line;
  bool too_long = false;
  while (lines_.Next(line, too_long)) {
    ++stats_.lines;
    if (stats_.lines > limits_.max_lines) {
      throw std::runtime_error(path_ + ": more than " + std::to_string(limits_.max_lines) +
                               " lines; raise --max-lines if the log really is that long");
    }
    const size_t first = line.find_first_not_of(" \t\r\v\f");
    if (first == std::string::npos || line[first] == '#') {
      ++stats_.comments;
      continue;
    }
    const ParseResult result =
        too_long ? Malformed("longer than " + std::to_string(limits_.MaxLineBytes()) +
                             " bytes, more than a line of " + std::to_string(limits_.max_beams) +
                             " beams can need (raise it with --max-beams)")
                 : Parse(line, record);
    if (result == ParseResult::kRecord) {
      (record.kind == CarmenRecord::Kind::kOdometry ? stats_.odometry : stats_.scans)++;
      return true;
    }
    if (result == ParseResult::kMalformed) {
      ++stats_.malformed;
      if (stats_.malformed_lines.size() < 5)
        stats_.malformed_lines.push_back({stats_.lines, reason_});
    }
  }
  return false;
}

std::string MalformedLinesText(const CarmenStats& stats, const std::string& path) {
  if (stats.malformed == 0) return "";
  std::string text = std::to_string(stats.malformed) + " malformed line" +
                     (stats.malformed == 1 ? "" : "s") + " of " + path + " left out\n";
  for (const auto& m : stats.malformed_lines) {
    text += "  line " + std::to_string(m.line) + ": " + m.reason + "\n";
  }
  if (stats.malformed > stats.malformed_lines.size()) {
    text += "  (" + std::to_string(stats.malformed - stats.malformed_lines.size()) + " more)\n";
  }
  return text;
}

}  // namespace structloc::log_formats
