// Saved pose file (see header).
#include "structloc/localisation/pose_state_file.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "structloc/config/output_file.hpp"
#include "structloc/world_model/world_model.hpp"

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
  // One line of seven numbers: a larger file is no saved pose.
  constexpr std::uintmax_t kMaxBytes = 4096;
  const auto bytes = std::filesystem::file_size(path, error);
  if (!error && bytes > kMaxBytes) {
    throw std::runtime_error(path + ": " + std::to_string(bytes) + " bytes, more than the " +
                             std::to_string(kMaxBytes) + " of a saved pose file");
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
  // Held to what --initial-pose accepts: a corrupt or planted file would
  // otherwise resume the localiser light years from the map.
  const double bound = world_model::WorldLimits::kDefaultMaxAbsCoordinateM;
  if (std::abs(s.map_to_odom.x) > bound || std::abs(s.map_to_odom.y) > bound ||
      std::abs(s.map_to_odom.theta) > 2.0 * geometry::kPi || s.variance.x() > bound * bound ||
      s.variance.y() > bound * bound || s.variance.z() > 4.0 * geometry::kPi * geometry::kPi) {
    throw std::runtime_error(path + ":1: the saved correction or its variances lie beyond " +
                             std::to_string(static_cast<long long>(bound)) +
                             " m (or one turn) of the map origin");
  }
  return s;
}

}  // namespace structloc::localisation
