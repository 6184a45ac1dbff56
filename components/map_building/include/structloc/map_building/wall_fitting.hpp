// The geometry every map maker shares (from scans, from grids, from drawings):
// a wall fitted by total least squares to all its supporting points (thesis
// 3.5.2, EQ 18 over the whole point set instead of one window), split where
// its points leave a gap (doors), and wall ends pulled to where two walls meet
// so that the world model derives the corner there. DDS-free.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <vector>

#include "structloc/geometry/line.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

struct FittedWall {
  geometry::Line line;      // (r, alpha) of the fitted line, map frame
  Eigen::Vector2d a{0, 0};  // extent: the supporting points projected on the line
  Eigen::Vector2d b{0, 0};
  double rms_m = 0.0;  // RMS of the perpendicular residuals
  size_t points = 0;   // supporting points
  size_t sources = 0;  // distinct scans (poses) that saw it; 0 when not known
  // Where it was seen from on average (map frame); NaN when not known.
  Eigen::Vector2d viewpoint{std::nan(""), std::nan("")};
  double Length() const { return (b - a).norm(); }
};

// Total least-squares line through `points` (at least two, not all in one
// place) with its extent and residual RMS; `sources` is left 0. Throws
// std::invalid_argument for fewer than two points or coincident points.
FittedWall FitWall(const std::vector<Eigen::Vector2d>& points);

// Position of `p` along the wall's direction (a -> b), metres from a.
double AlongWall(const FittedWall& wall, const Eigen::Vector2d& p);

// Splits points that lie on one line into runs whose consecutive points (in
// order along the line) are at most `max_gap_m` apart; returns the runs'
// points. The order of `points` does not matter.
std::vector<std::vector<Eigen::Vector2d>> SplitAtGaps(const FittedWall& wall,
                                                      const std::vector<Eigen::Vector2d>& points,
                                                      double max_gap_m);

struct CornerJoinOptions {
  double max_end_distance_m = 0.15;  // a wall end this close to the intersection is moved onto it
  double min_angle_rad = 0.5;        // walls meeting at less than ~29 deg are not joined
};

// Moves the ends of two walls that nearly meet onto their lines'
// intersection (the end of each nearer to it, when within max_end_distance_m,
// and only when the intersection lies within or just beyond both walls).
// Returns whether it did.
bool JoinWallEnds(FittedWall& first, FittedWall& second, const CornerJoinOptions& options);

// JoinWallEnds on every pair of walls (i, j > i) in the order of a double
// loop over the pairs, each pair with the ends as earlier joins left them;
// only pairs whose ends lie near each other are tried, found by cell, so the
// time grows with the walls, not with their pairs. Returns how many corners
// were joined.
size_t JoinCorners(std::vector<FittedWall>& walls, const CornerJoinOptions& options);

// Removes the walls shorter than min_length_m (joining corners shortens
// walls: an end can move by max_end_distance_m); returns how many.
size_t DropShortWalls(std::vector<FittedWall>& walls, double min_length_m);

// A world model of the walls (ids 1..n in order) and cylinders (ids 1..m);
// corners are derived by the world model where wall ends meet.
world_model::WorldModel MakeWorld(const std::string& name, const std::vector<FittedWall>& walls,
                                  const std::vector<world_model::Cylinder>& cylinders);

}  // namespace structloc::map_building
