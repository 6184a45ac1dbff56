// Free conversions between ROS 2 messages and the localisation core's types,
// tested without a participant.
#pragma once

#include <string>

#include "geometry_msgs/msg/PoseArray.h"
#include "geometry_msgs/msg/PoseWithCovarianceStamped.h"
#include "nav_msgs/msg/Odometry.h"
#include "sensor_msgs/msg/LaserScan.h"
#include "structloc/dds_common/diagnostics.hpp"
#include "structloc/dds_common/topics.hpp"
#include "structloc/localisation_core/global/hypothesis_tracker.hpp"
#include "structloc/localisation_core/scan/session_scan.hpp"
#include "structloc/localisation_core/tracking/pose_tracker.hpp"
#include "structloc/localisation_core/tracking/session_health.hpp"
#include "structloc_msgs/msg/LocalisationStatus.h"
#include "structloc_msgs/msg/ScanFeatures.h"
#include "tf2_msgs/msg/TFMessage.h"

namespace structloc::localisation {

// The ranges stay owned by the message.
localisation_core::ScanInput FromLaserScan(const sensor_msgs::msg::LaserScan& msg);
// The scan with a copy of its ranges, to wait in a localisation_core::TrackingSession.
localisation_core::SessionScan ToSessionScan(const sensor_msgs::msg::LaserScan& msg);
struct StampedPose2D {
  double stamp;
  geometry::Pose2D pose;
};
StampedPose2D FromOdometry(const nav_msgs::msg::Odometry& msg);
// Pose and the x, y, yaw block of the covariance.
StampedPose2D FromPoseWithCovariance(const geometry_msgs::msg::PoseWithCovarianceStamped& msg,
                                     Eigen::Matrix3d* covariance);

// Outputs are stamped with the frame ids of `frames`.
geometry_msgs::msg::PoseWithCovarianceStamped ToPoseWithCovarianceStamped(
    const localisation_core::TrackedPose& pose, const dds_common::FrameIds& frames);
tf2_msgs::msg::TFMessage ToMapToOdomTf(const geometry::Pose2D& map_to_odom, double stamp,
                                       const dds_common::FrameIds& frames);
structloc_msgs::msg::ScanFeatures ToScanFeatures(
    const localisation_core::LocalisationResult& result, double stamp,
    const dds_common::FrameIds& frames);
// `lost_reason`: the tracker's verdict on the scan (empty: not lost).
structloc_msgs::msg::LocalisationStatus ToStatus(
    const localisation_core::LocalisationResult& result, const char* lost_reason,
    const localisation_core::TrackerStats& stats, uint64_t dropped, double stamp,
    const dds_common::FrameIds& frames);

// The hypotheses of a robot without a pose, best first, in the map frame.
geometry_msgs::msg::PoseArray ToPoseArray(
    const std::vector<localisation_core::Hypothesis>& hypotheses, double stamp,
    const dds_common::FrameIds& frames);
// The status while no pose is tracked: `phase` "searching" or "holding"
// (with the hypotheses' weights, their likelihoods normalised to sum 1).
structloc_msgs::msg::LocalisationStatus ToStartUpStatus(
    const std::vector<localisation_core::Hypothesis>& hypotheses, double stamp,
    const dds_common::FrameIds& frames);

// The core's health assessment as the DDS layer's diagnostics report.
dds_common::HealthReport ToHealthReport(const localisation_core::SessionHealth& health);

}  // namespace structloc::localisation
