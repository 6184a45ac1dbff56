// Saved pose file (see header).
#include "structloc/localisation/pose_state_file.hpp"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "structloc/config/output_file.hpp"

namespace structloc::localisation {

void SavePoseAtomically(const std::string& path, const SavedPose& s) {
  config::OutputFile out(path);
  out.Stream() << std::setprecision(12) << "map_to_odom " << s.map_to_odom.x << " "
               << s.map_to_odom.y << " " << s.map_to_odom.theta << " " << s.variance.x() << " "
               << s.variance.y() << " " << s.variance.z() << "\n";
  out.Commit();
}

std::optional<SavedPose> LoadSavedPose(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return std::nullopt;
  if (std::filesystem::is_directory(path, error)) {
    throw std::runtime_error(path + ": is a folder, not a saved pose file");
  }
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
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
