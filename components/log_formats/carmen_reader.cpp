// CARMEN log reader (see header).
#include "carmen_reader.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace structloc::logs {

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

CarmenReader::CarmenReader(const std::string& path) : path_(path) {
  const bool gz = path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0;
  if (gz) {
    if (FILE* probe = std::fopen(path.c_str(), "rb")) {
      std::fclose(probe);
    } else {
      throw std::runtime_error(path + ": cannot open the log");
    }
    const std::string cmd = "gzip -dc '" + path + "'";
    file_ = popen(cmd.c_str(), "r");
    pipe_ = true;
  } else {
    file_ = std::fopen(path.c_str(), "r");
  }
  if (file_ == nullptr) throw std::runtime_error(path + ": cannot open the log");
}

CarmenReader::~CarmenReader() {
  if (file_ == nullptr) return;
  if (pipe_) {
    pclose(file_);
  } else {
    std::fclose(file_);
  }
}

namespace {
bool ReadPose(std::istringstream& in, geometry::Pose2D* p) {
  return static_cast<bool>(in >> p->x >> p->y >> p->theta) && geometry::IsFinite(*p);
}
bool ReadRanges(std::istringstream& in, size_t n, std::vector<float>* ranges) {
  if (n > 100000) return false;
  ranges->resize(n);
  for (size_t i = 0; i < n; ++i) {
    double r;
    if (!(in >> r)) return false;
    (*ranges)[i] = static_cast<float>(r);
  }
  return true;
}
}  // namespace

CarmenReader::ParseResult CarmenReader::Parse(const std::string& text, CarmenRecord& r) {
  constexpr auto kRecord = ParseResult::kRecord;
  constexpr auto kSkipped = ParseResult::kSkipped;
  constexpr auto kMalformed = ParseResult::kMalformed;
  std::istringstream in(text);
  std::string tag;
  in >> tag;
  r = CarmenRecord{};
  r.tag = tag;
  r.line = stats_.lines;
  if (tag == "ODOM") {
    geometry::Pose2D p;
    double accel;
    if (!ReadPose(in, &p) || !(in >> r.linear >> r.angular >> accel >> r.stamp)) return kMalformed;
    r.kind = CarmenRecord::Kind::kOdometry;
    r.robot_pose = p;
    return kRecord;
  }
  if (tag == "FLASER" || tag == "RLASER") {
    size_t n;
    geometry::Pose2D laser, robot;
    if (!(in >> n) || !ReadRanges(in, n, &r.ranges) || !ReadPose(in, &laser) ||
        !ReadPose(in, &robot) || !(in >> r.stamp)) {
      return kMalformed;
    }
    FlaserGeometry(n, &r.start_angle, &r.angular_resolution);
    r.kind = CarmenRecord::Kind::kScan;
    r.laser_pose = laser;
    r.robot_pose = robot;
    return kRecord;
  }
  if (tag.rfind("RAWLASER", 0) == 0 || tag.rfind("ROBOTLASER", 0) == 0) {
    int type;
    double fov, accuracy, remission_mode;
    size_t n, m;
    if (!(in >> type >> r.start_angle >> fov >> r.angular_resolution >> r.max_range >> accuracy >>
          remission_mode >> n) ||
        !ReadRanges(in, n, &r.ranges) || !(in >> m) || m > 100000) {
      return kMalformed;
    }
    std::vector<float> remissions;
    if (!ReadRanges(in, m, &remissions)) return kMalformed;
    r.kind = CarmenRecord::Kind::kScan;
    if (tag.rfind("ROBOTLASER", 0) == 0) {
      geometry::Pose2D laser, robot;
      double fsd, ssd, turn;
      if (!ReadPose(in, &laser) || !ReadPose(in, &robot) ||
          !(in >> r.linear >> r.angular >> fsd >> ssd >> turn)) {
        return kMalformed;
      }
      r.laser_pose = laser;
      r.robot_pose = robot;
    }
    return (in >> r.stamp) ? kRecord : kMalformed;
  }
  if (tag == "PARAM") {
    std::string name;
    double value;
    if (in >> name >> value && name == "structloc_laser_time_increment") time_increment_ = value;
    ++stats_.skipped["PARAM"];
    return kSkipped;
  }
  ++stats_.skipped[tag];
  return kSkipped;
}

bool CarmenReader::Next(CarmenRecord& record) {
  char buffer[1 << 16];
  std::string line;
  while (std::fgets(buffer, sizeof(buffer), file_) != nullptr) {
    line.assign(buffer);
    while (!line.empty() && line.back() != '\n' && std::fgets(buffer, sizeof(buffer), file_)) {
      line.append(buffer);
    }
    ++stats_.lines;
    if (line.empty() || line[0] == '#' || line[0] == '\n') {
      ++stats_.comments;
      continue;
    }
    const ParseResult result = Parse(line, record);
    if (result == ParseResult::kRecord && std::isfinite(record.stamp)) {
      (record.kind == CarmenRecord::Kind::kOdometry ? stats_.odometry : stats_.scans)++;
      return true;
    }
    if (result != ParseResult::kSkipped) {
      ++stats_.malformed;
      if (stats_.malformed_lines.size() < 5) stats_.malformed_lines.push_back(stats_.lines);
    }
  }
  return false;
}

}  // namespace structloc::logs
