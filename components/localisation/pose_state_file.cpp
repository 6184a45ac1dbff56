// Saved pose file (see header).
#include "pose_state_file.hpp"

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <stdexcept>

namespace structloc::localisation {

void SavePoseAtomically(const std::string& path, const SavedPose& s) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << std::setprecision(12) << s.pose.x << " " << s.pose.y << " " << s.pose.theta << " "
        << s.variance.x() << " " << s.variance.y() << " " << s.variance.z() << "\n";
    out.flush();
    if (!out) throw std::runtime_error(tmp + ": cannot write the saved pose");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    throw std::runtime_error(path + ": cannot replace the saved pose");
  }
}

std::optional<SavedPose> LoadSavedPose(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  SavedPose s;
  if (!(in >> s.pose.x >> s.pose.y >> s.pose.theta >> s.variance.x() >> s.variance.y() >>
        s.variance.z()) ||
      !geometry::IsFinite(s.pose) || !s.variance.allFinite() || (s.variance.array() <= 0).any()) {
    throw std::runtime_error(path + ":1: saved pose is not \"x y theta var_x var_y var_theta\"");
  }
  return s;
}

}  // namespace structloc::localisation
