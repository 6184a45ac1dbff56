// The pose-and-wall refinement that ends SLAM: the pose graph ties each
// keyframe to its neighbours and to the loops it closes, so a heading error
// between loop closures bends the corridors it drives along. A straight wall
// seen from many keyframes ties them all to one line. Each keyframe's straight
// segments (the thesis' line fits, 3.5.2, EQ 18) are associated with the
// building's walls (a wall seen on two passes ties them, as a loop closure
// does), and the keyframe poses and the walls' lines (r, alpha) are optimised
// together with the graph's edges (Ceres Solver, a robust loss); association
// and optimisation alternate for a few rounds. DDS-free.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/slam_core/pose_graph.hpp"

namespace structloc::slam_core {

struct WallRefinementOptions {
  bool enabled = true;  // false: SLAM ends with the pose graph's optimum
  int rounds = 3;       // association and optimisation, alternating
  // A keyframe's segment belongs to a wall facing the same way within this ...
  double max_angle_rad = 0.05;
  // ... whose line both its ends lie within this of ...
  double max_offset_m = 0.1;
  // ... and which it overlaps or comes this close to along it.
  double max_gap_m = 0.5;
  // A segment end's standard deviation across its wall: from the segment's
  // fit, counting one point in this many (neighbours see the same stretch of
  // wall), never below min_sigma_m.
  double correlated_points = 10.0;
  double min_sigma_m = 0.01;
  // The Cauchy loss's scale, in standard deviations: an end this far from
  // its wall counts half as much as a quadratic one, and a segment given to
  // the wrong wall (a wrong loop closure, across passes) little.
  double robust_scale_sigmas = 2.0;
};

// A straight segment of one keyframe's scan, in the keyframe's frame.
struct KeyframeSegment {
  Eigen::Vector2d a{0, 0};
  Eigen::Vector2d b{0, 0};
  double rms_m = 0.0;  // of its points across the fitted line
  size_t points = 0;
};

// The straight segments of a scan (points in beam order, in its own frame),
// as the map builder finds them.
std::vector<KeyframeSegment> FindKeyframeSegments(const std::vector<Eigen::Vector2d>& points);

struct WallRefinementSummary {
  size_t walls = 0;         // walls seen from two keyframes or more (the last round's)
  size_t observations = 0;  // segments associated with them
  bool usable = true;       // every round's solve ended with a usable solution
};

// Refines `poses` (keyframe estimates, the graph's optimum on entry) under
// `edges` and the walls their `segments` (one list per keyframe) see. Throws
// std::invalid_argument when `segments` and `poses` differ in length, and as
// OptimisePoseGraph does for a malformed edge.
WallRefinementSummary RefineWithWalls(std::vector<geometry::Pose2D>& poses,
                                      const std::vector<std::vector<KeyframeSegment>>& segments,
                                      const std::vector<PoseGraphEdge>& edges,
                                      const WallRefinementOptions& options,
                                      const PoseGraphOptions& graph);

}  // namespace structloc::slam_core
