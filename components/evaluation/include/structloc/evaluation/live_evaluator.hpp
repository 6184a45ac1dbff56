// Watches a running system over DDS and judges it against the simulator's
// ground truth: collects rt/ground_truth, rt/odom, rt/pose and the
// localisation status, and computes the localised and odometry-only errors.
// Used by "structloc demo" and by the integration tests.
#pragma once

#include <mutex>
#include <string>
#include <vector>

#include "structloc/dds_common/node.hpp"
#include "structloc/geometry/pose2d.hpp"
#include "structloc/replay/trajectory_error.hpp"

namespace structloc::evaluation {

struct LiveSnapshot {
  double sim_time_s = 0.0;       // since the first ground-truth sample
  double position_error_m = -1;  // latest pose vs truth at its stamp (-1: none yet)
  double heading_error_rad = 0;
  int matched_features = 0, expected_features = 0;
  double quality = 0.0;
  bool lost = false;
  uint64_t poses = 0;
};

class LiveEvaluator {
 public:
  // `initial_pose`: the robot's map pose at odometry's origin (for odometry-only paths).
  LiveEvaluator(dds_common::Node& node, const geometry::Pose2D& initial_pose);
  LiveEvaluator(const LiveEvaluator&) = delete;
  LiveEvaluator& operator=(const LiveEvaluator&) = delete;

  LiveSnapshot Snapshot();
  std::vector<log_formats::StampedPose> Truth();
  std::vector<log_formats::StampedPose> Estimate();
  // When each pose arrived (steady-clock seconds), for pose_age.hpp.
  std::vector<double> PoseArrivals();
  std::vector<log_formats::StampedPose> OdometryInMap();
  uint64_t LostCount();
  replay::TrajectoryError EstimateError();
  replay::TrajectoryError OdometryError();
  // Fig. 44 of the thesis: true path, odometry, localised estimate; throws on I/O errors.
  void RenderFigure(const std::string& map_path, const std::string& png_path,
                    const std::string& title);

 private:
  dds_common::Node& node_;
  std::mutex mutex_;
  geometry::Pose2D initial_pose_;
  std::vector<log_formats::StampedPose> truth_, estimate_, odometry_;
  std::vector<double> pose_arrivals_s_;
  LiveSnapshot snapshot_;
  uint64_t lost_ = 0;
  // Last: destroyed first, so no callback reaches the members above then.
  std::vector<dds_common::Subscription> subscriptions_;
};

}  // namespace structloc::evaluation
