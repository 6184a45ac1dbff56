// One rigid motion (rotation and translation, no scale) that brings an
// estimated trajectory onto ground truth: the least-squares fit over the
// positions matched by time (Umeyama 1991 without scale, in closed form in
// 2-D). A path or a map that has a frame of its own (SLAM's, a self-built
// map's) is judged after that frame's offset is taken out. DDS-free.
#pragma once

#include <optional>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/log_formats/tum_reader.hpp"
#include "structloc/replay/trajectory_error.hpp"

namespace structloc::replay {

// The motion that, composed on every pose of `estimate`, brings its positions
// closest to those of `truth` (sorted by stamp) at the same stamps (within
// `tolerance_s`); none when fewer than two poses match or the matched
// positions do not spread (a rotation about one point is undetermined).
std::optional<geometry::Pose2D> AlignTrajectory(
    const std::vector<log_formats::StampedPose>& estimate,
    const std::vector<log_formats::StampedPose>& truth, double tolerance_s = 0.02);

// The errors of `estimate` against `truth` after AlignTrajectory's motion;
// none when there is no alignment.
std::optional<TrajectoryError> CompareAligned(const std::vector<log_formats::StampedPose>& estimate,
                                              const std::vector<log_formats::StampedPose>& truth,
                                              double tolerance_s = 0.02);

// Every pose of `trajectory` with `motion` composed on it (motion * pose).
std::vector<log_formats::StampedPose> Moved(const std::vector<log_formats::StampedPose>& trajectory,
                                            const geometry::Pose2D& motion);

}  // namespace structloc::replay
