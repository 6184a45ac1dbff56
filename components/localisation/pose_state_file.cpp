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
    out << std::setprecision(12) << "map_to_odom " << s.map_to_odom.x << " " << s.map_to_odom.y
        << " " << s.map_to_odom.theta << " " << s.variance.x() << " " << s.variance.y() << " "
        << s.variance.z() << "\n";
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
  std::string tag;
  if (!(in >> tag >> s.map_to_odom.x >> s.map_to_odom.y >> s.map_to_odom.theta >> s.variance.x() >>
        s.variance.y() >> s.variance.z()) ||
      tag != "map_to_odom" || !geometry::IsFinite(s.map_to_odom) || !s.variance.allFinite() ||
      (s.variance.array() <= 0).any()) {
    throw std::runtime_error(path + ":1: not \"map_to_odom X Y THETA VAR_X VAR_Y VAR_THETA\"");
  }
  return s;
}

}  // namespace structloc::localisation
