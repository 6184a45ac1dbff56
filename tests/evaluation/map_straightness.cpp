// How straight a map of a rectilinear building is, with no reference: the
// building's axes are the length-weighted mean direction of its long walls
// modulo 90 deg (a circular mean of four times each wall's angle), and
// printed are the share of long-wall length within 1 deg of those axes and,
// band by band along x, the mean deviation of the walls within 5 deg of them.
// A map bent by its poses' heading errors has walls turning from one end of
// the building to the other, where the building's own walls are straight and
// square. Used to ask which of two maps of one recording (the one built on
// the corrected poses, the one built on a SLAM path) follows the building
// better (issue 41).
//   structloc_map_straightness WORLD.xml [MIN_LENGTH_M=2] [BAND_M=5]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>

#include "structloc/world_model/world_model_xml.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// `angle` less `axis`, modulo 90 deg, within (-45, 45] deg.
double Deviation(double angle, double axis) {
  double d = std::fmod(angle - axis, kPi / 2);
  if (d > kPi / 4) d -= kPi / 2;
  if (d <= -kPi / 4) d += kPi / 2;
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: structloc_map_straightness WORLD.xml [MIN_LENGTH_M=2] [BAND_M=5]\n");
    return 2;
  }
  try {
    const double min_length_m = argc > 2 ? std::atof(argv[2]) : 2.0;
    const double band_m = argc > 3 ? std::atof(argv[3]) : 5.0;
    if (!(min_length_m > 0) || !(band_m > 0))
      throw std::invalid_argument("MIN_LENGTH_M and BAND_M must be > 0");
    const auto world = structloc::world_model::LoadWorldModel(argv[1]);
    double c = 0.0, s = 0.0, length = 0.0;
    for (const auto& w : world.Walls()) {
      if (w.Length() < min_length_m) continue;
      const Eigen::Vector2d d = w.b - w.a;
      const double angle = std::atan2(d.y(), d.x());
      c += w.Length() * std::cos(4 * angle);
      s += w.Length() * std::sin(4 * angle);
      length += w.Length();
    }
    if (length == 0.0) throw std::invalid_argument("no wall is at least MIN_LENGTH_M long");
    const double axis = std::atan2(s, c) / 4;
    double within = 0.0;
    struct Band {
      double length = 0.0, weighted = 0.0;
    };
    std::map<long, Band> bands;
    for (const auto& w : world.Walls()) {
      if (w.Length() < min_length_m) continue;
      const Eigen::Vector2d d = w.b - w.a;
      const double deviation = Deviation(std::atan2(d.y(), d.x()), axis);
      if (std::abs(deviation) < 1 * kDeg) within += w.Length();
      if (std::abs(deviation) >= 5 * kDeg) continue;
      auto& band = bands[std::lround(std::floor(0.5 * (w.a.x() + w.b.x()) / band_m))];
      band.length += w.Length();
      band.weighted += w.Length() * deviation;
    }
    std::printf(
        "%s: axes at %.2f deg; %.0f %% of %.0f m of walls %.0f m or longer within 1 deg of them\n",
        argv[1], axis / kDeg, 100 * within / length, length, min_length_m);
    for (const auto& [k, band] : bands) {
      std::printf("  x %6.1f to %6.1f m: %5.1f m of walls, their mean deviation %+.2f deg\n",
                  k * band_m, (k + 1) * band_m, band.length, band.weighted / band.length / kDeg);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "structloc_map_straightness: %s\n", e.what());
    return 1;
  }
}
