// Calibration input files (see header).
#include "calibration_data.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace structloc::calibration {
namespace {

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

std::ifstream Open(const std::string& path, std::string* header) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  if (!std::getline(in, *header)) throw std::runtime_error(path + ": empty file (no header)");
  while (!header->empty() && (header->back() == '\r' || header->back() == ' ')) header->pop_back();
  return in;
}

}  // namespace

std::vector<EncoderSample> ReadEncodersCsv(const std::string& path) {
  std::string header;
  auto in = Open(path, &header);
  if (header != "t,traction_ticks,steering_ticks") {
    throw std::runtime_error(path + ":1: header must be 't,traction_ticks,steering_ticks', not '" +
                             header + "'");
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
    const double ticks = Number(path, n, f[1], false);
    if (ticks < 0 || ticks != std::floor(ticks)) {
      throw std::runtime_error(path + ":" + std::to_string(n) +
                               ": traction_ticks must be a non-negative integer");
    }
    s.traction_ticks = static_cast<uint64_t>(ticks);
    s.steering_ticks = Number(path, n, f[2], false);
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
    if (!geometry::IsFinite(fix.pose) || !fix.variance.allFinite() ||
        (fix.variance.array() < 0).any()) {
      ++file.dropped_non_finite;
      continue;
    }
    file.fixes.push_back(fix);
  }
  if (file.fixes.size() < 3) throw std::runtime_error(path + ": fewer than three usable fixes");
  return file;
}

}  // namespace structloc::calibration
