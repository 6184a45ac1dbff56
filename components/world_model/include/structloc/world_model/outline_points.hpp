// The map's outline as points: every wall and pillar outline sampled at a
// fixed spacing. The global localiser draws its distance field from them and
// the search for the map's twins checks a motion against them.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "structloc/world_model/world_model.hpp"

namespace structloc::world_model {

// Points at most `step_m` apart along each wall (both ends included) and
// around each pillar's outline (at least `min_pillar_points` of them), walls
// first, in the map's order.
std::vector<Eigen::Vector2d> OutlinePoints(const WorldModel& world, double step_m,
                                           int min_pillar_points);

}  // namespace structloc::world_model
