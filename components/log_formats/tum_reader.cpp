// TUM trajectory reader (see header).
#include "structloc/log_formats/tum_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace structloc::log_formats {

std::vector<StampedPose> ReadTum(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw std::runtime_error(path + ": is a folder, not a TUM trajectory");
  }
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<StampedPose> poses;
  std::string line;
  for (size_t n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    double t, x, y, z, qx, qy, qz, qw;
    if (!(ss >> t >> x >> y >> z >> qx >> qy >> qz >> qw) || !std::isfinite(t + x + y + qz + qw)) {
      throw std::runtime_error(path + ":" + std::to_string(n) +
                               ": not a TUM line (t x y z qx qy qz qw)");
    }
    const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
    poses.push_back({t, {x, y, yaw}});
  }
  std::sort(poses.begin(), poses.end(),
            [](const StampedPose& a, const StampedPose& b) { return a.stamp < b.stamp; });
  return poses;
}

const StampedPose* Nearest(const std::vector<StampedPose>& sorted, double stamp, double tolerance) {
  auto it = std::lower_bound(sorted.begin(), sorted.end(), stamp,
                             [](const StampedPose& p, double t) { return p.stamp < t; });
  const StampedPose* best = nullptr;
  double best_dt = tolerance;
  for (auto c : {it, it == sorted.begin() ? it : it - 1}) {
    if (c == sorted.end()) continue;
    const double dt = std::abs(c->stamp - stamp);
    if (dt <= best_dt) {
      best_dt = dt;
      best = &*c;
    }
  }
  return best;
}

}  // namespace structloc::log_formats
