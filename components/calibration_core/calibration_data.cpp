// Calibration input files (see header).
#include "structloc/calibration_core/calibration_data.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace structloc::calibration_core {
namespace {

constexpr double kMaxFixCoordinate_m = 1e5;  // as the world model's bound

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string field;
  while (std::getline(ss, field, ',')) {
    while (!field.empty() && (field.back() == '\r' || field.back() == ' ')) field.pop_back();
    out.push_back(field);
  }
  return out;
}

double Number(const std::string& path, size_t line, const std::string& text, bool allow_nan) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || (!allow_nan && !std::isfinite(v))) {
    throw std::runtime_error(path + ":" + std::to_string(line) + ": '" + text +
                             "' is not a finite number");
  }
  return v;
}

std::string Where(const std::string& path, size_t line) {
  return path + ":" + std::to_string(line) + ": ";
}

// A raw counter value: decimal digits only (no sign, exponent or fraction),
// at most `max_value`.
uint64_t Ticks(const std::string& path, size_t line, const std::string& text, uint64_t max_value,
               int bits) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    throw std::runtime_error(Where(path, line) + "'" + text +
                             "' is not a non-negative integer (wheel ticks hold the raw "
                             "counter value)");
  }
  errno = 0;
  const unsigned long long value = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE || value > max_value) {
    throw std::runtime_error(Where(path, line) + "counter value " + text + " does not fit a " +
                             std::to_string(bits) + "-bit counter (largest " +
                             std::to_string(max_value) + "); check the robot file's counter bits");
  }
  return value;
}

std::ifstream Open(const std::string& path, std::string* header) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  if (!std::getline(in, *header)) throw std::runtime_error(path + ": empty file (no header)");
  const std::string byte_order_mark = "\xEF\xBB\xBF";
  if (header->rfind(byte_order_mark, 0) == 0) header->erase(0, byte_order_mark.size());
  while (!header->empty() && (header->back() == '\r' || header->back() == ' ')) header->pop_back();
  return in;
}

}  // namespace

std::string DescribeDropped(const FixesFile& file) {
  const size_t nan = file.dropped_non_finite - file.dropped_infinite;
  const size_t total = file.dropped_non_finite + file.dropped_negative_variance;
  if (total == 0) return "none dropped";
  std::string text = std::to_string(total) + " dropped (";
  std::string separator;
  auto add = [&](size_t count, const char* what) {
    if (count == 0) return;
    text += separator + std::to_string(count) + " with " + what;
    separator = ", ";
  };
  add(nan, "NaN");
  add(file.dropped_infinite, "an infinite value");
  add(file.dropped_negative_variance, "a negative variance");
  return text + "; first at line " + std::to_string(file.first_dropped_line) + ")";
}

std::vector<EncoderSample> ReadEncodersCsv(const std::string& path, int traction_counter_bits,
                                           kinematics::DriveKind kind) {
  if (traction_counter_bits < 1 || traction_counter_bits > 64) {
    throw std::invalid_argument("ReadEncodersCsv: traction_counter_bits must be 1..64");
  }
  const uint64_t max_ticks =
      traction_counter_bits == 64 ? UINT64_MAX : (uint64_t{1} << traction_counter_bits) - 1;
  std::string header;
  auto in = Open(path, &header);
  const bool differential = kind == kinematics::DriveKind::kDifferential;
  const std::string expected =
      differential ? "t,left_ticks,right_ticks" : "t,traction_ticks,steering_ticks";
  if (header != expected) {
    const std::string other =
        differential ? "t,traction_ticks,steering_ticks" : "t,left_ticks,right_ticks";
    throw std::runtime_error(
        path + ":1: header must be '" + expected + "' for a " +
        (differential ? "differential-drive" : "tricycle") + " robot, not '" + header + "'" +
        (header == other ? " (the robot file's kind and the encoder file disagree)" : ""));
  }
  std::vector<EncoderSample> samples;
  std::string line;
  for (size_t n = 2; std::getline(in, line); ++n) {
    if (line.empty() || line == "\r") continue;
    const auto f = SplitCsv(line);
    if (f.size() != 3)
      throw std::runtime_error(path + ":" + std::to_string(n) + ": expected 3 fields");
    EncoderSample s;
    s.t = Number(path, n, f[0], false);
    if (differential) {
      s.left_ticks = Ticks(path, n, f[1], max_ticks, traction_counter_bits);
      s.right_ticks = Ticks(path, n, f[2], max_ticks, traction_counter_bits);
    } else {
      s.traction_ticks = Ticks(path, n, f[1], max_ticks, traction_counter_bits);
      s.steering_ticks = Number(path, n, f[2], false);
    }
    if (!samples.empty() && !(s.t > samples.back().t)) {
      throw std::runtime_error(path + ":" + std::to_string(n) + ": time " + f[0] +
                               " is not after the previous line's (times must increase)");
    }
    samples.push_back(s);
  }
  if (samples.size() < 2) throw std::runtime_error(path + ": fewer than two encoder samples");
  return samples;
}

FixesFile ReadFixesCsv(const std::string& path) {
  std::string header;
  auto in = Open(path, &header);
  const bool variances = header == "t,x,y,theta,var_x,var_y,var_theta";
  if (!variances && header != "t,x,y,theta") {
    throw std::runtime_error(
        path + ":1: header must be 't,x,y,theta' (optionally ',var_x,var_y,var_theta')");
  }
  FixesFile file;
  std::string line;
  double last_t = -INFINITY;
  for (size_t n = 2; std::getline(in, line); ++n) {
    if (line.empty() || line == "\r") continue;
    const auto f = SplitCsv(line);
    if (f.size() != (variances ? 7u : 4u)) {
      throw std::runtime_error(path + ":" + std::to_string(n) + ": expected " +
                               std::to_string(variances ? 7 : 4) + " fields");
    }
    Fix fix;
    fix.t = Number(path, n, f[0], false);
    if (!(fix.t > last_t)) {
      throw std::runtime_error(path + ":" + std::to_string(n) + ": time " + f[0] +
                               " is not after the previous line's (times must increase)");
    }
    last_t = fix.t;
    fix.pose = {Number(path, n, f[1], true), Number(path, n, f[2], true),
                Number(path, n, f[3], true)};
    if (variances) {
      fix.has_variance = true;
      fix.variance = {Number(path, n, f[4], true), Number(path, n, f[5], true),
                      Number(path, n, f[6], true)};
    }
    const bool has_nan = std::isnan(fix.pose.x) || std::isnan(fix.pose.y) ||
                         std::isnan(fix.pose.theta) || fix.variance.hasNaN();
    const bool finite = geometry::IsFinite(fix.pose) && fix.variance.allFinite();
    const bool negative_variance = (fix.variance.array() < 0).any();
    if (!finite || negative_variance) {
      if (!finite) ++file.dropped_non_finite;
      if (!finite && !has_nan) ++file.dropped_infinite;
      if (finite) ++file.dropped_negative_variance;
      if (file.first_dropped_line == 0) file.first_dropped_line = n;
      continue;
    }
    // Positions a building cannot have are a broken file, not noise to drop.
    if (std::abs(fix.pose.x) > kMaxFixCoordinate_m || std::abs(fix.pose.y) > kMaxFixCoordinate_m) {
      throw std::runtime_error(path + ":" + std::to_string(n) + ": position (" + f[1] + ", " +
                               f[2] + ") is more than 100 km from the map origin");
    }
    file.fixes.push_back(fix);
  }
  if (file.fixes.size() < 3) throw std::runtime_error(path + ": fewer than three usable fixes");
  return file;
}

}  // namespace structloc::calibration_core
