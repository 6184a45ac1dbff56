// The places a map cannot tell apart: rigid motions of the plane that carry
// the map onto itself, such as a hall that looks the same turned by 180 deg
// about its centre but for one niche. A robot tracked at the twin of where it
// is (carried there, or committed there) fits every scan as well as at its
// true pose except where the map's one differing detail is in view: neither
// the share of the scan the tracked pose explains (KidnapWatch) nor a global
// search (which finds both places) can tell, and TwinWatch compares the two.
// A motion is a twin when it carries at least min_overlap of the map's
// outline (walls and pillar outlines, sampled along their length) to within a
// few centimetres of the outline; the motions tried carry one of the longest
// walls onto another of the same length, either way round. DDS-free,
// deterministic.
#pragma once

#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/localisation_core/global/global_localiser.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::localisation_core {

struct MapTwinOptions {
  double min_overlap = 0.9;         // share of the outline carried onto the outline
  double sample_step_m = 0.1;       // the outline is sampled this often
  int longest_walls = 24;           // the motions tried carry one of these walls onto another ...
  double min_wall_m = 1.0;          // ... of at least this length ...
  double length_tolerance_m = 0.1;  // ... whose lengths differ by at most this
  // A sample carried to where GlobalLocaliser::SurfaceGain is at least this
  // lies on the outline (about 7 cm with the ranking's 0.15 m truncation).
  double on_outline_gain = 0.8;
  // TwinWatch: the scan points one evidence step may tell the tracked pose
  // and its twin apart by without counting (Page's reference value): a
  // person or a box that happens to fall on a surface at one of them.
  double allowance_points = 1.0;
};

// Throws std::invalid_argument naming the option when one is out of range.
void CheckMapTwinOptions(const MapTwinOptions& options);

// The twins of `world`, each as the motion T that carries a place to its twin
// (map frame: turned by T.theta about the origin, then shifted by (T.x,
// T.y)); the twin of robot pose P is Compose(T, P). Motions that turn by no
// more than the localiser's distinct_heading_rad and shift the origin by no
// more than its distinct_distance_m (the identity) are not twins.
// `localiser` holds the distance field of the same world.
std::vector<geometry::Pose2D> FindMapTwins(const world_model::WorldModel& world,
                                           const GlobalLocaliser& localiser,
                                           const MapTwinOptions& options = {});

}  // namespace structloc::localisation_core
