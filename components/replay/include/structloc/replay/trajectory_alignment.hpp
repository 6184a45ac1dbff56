// One rigid motion (rotation and translation, no scale) that brings an
// estimated trajectory onto ground truth: the least-squares fit over the
// positions matched by time (Umeyama 1991 without scale, in closed form in
// 2-D). A path or a map that has a frame of its own (SLAM's, a self-built
// map's) is judged after that frame's offset is taken out. With a scale as
// well (Umeyama with scale): how much of what remains is the two
// trajectories' scale, as when a reference path's steps are longer than its
// scans say. DDS-free.
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

// A motion after a scale about the origin: a position p goes to
// motion * (scale p), a heading turns by the motion's.
struct Similarity {
  geometry::Pose2D motion;
  double scale = 1.0;
};

// AlignTrajectory with a scale of the estimate's positions fitted as well.
std::optional<Similarity> AlignTrajectoryWithScale(
    const std::vector<log_formats::StampedPose>& estimate,
    const std::vector<log_formats::StampedPose>& truth, double tolerance_s = 0.02);

// The errors of `estimate` against `truth` after AlignTrajectoryWithScale's
// similarity, and its scale; none when there is no alignment.
struct ScaledError {
  double scale = 1.0;
  TrajectoryError error;
};
std::optional<ScaledError> CompareAlignedWithScale(
    const std::vector<log_formats::StampedPose>& estimate,
    const std::vector<log_formats::StampedPose>& truth, double tolerance_s = 0.02);

// Every pose of `trajectory` with `motion` composed on it (motion * pose).
std::vector<log_formats::StampedPose> Moved(const std::vector<log_formats::StampedPose>& trajectory,
                                            const geometry::Pose2D& motion);
// Every pose of `trajectory` under `similarity`.
std::vector<log_formats::StampedPose> Moved(const std::vector<log_formats::StampedPose>& trajectory,
                                            const Similarity& similarity);

}  // namespace structloc::replay
