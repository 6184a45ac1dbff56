// Free conversions between ROS 2 messages and the localisation core's types,
// tested without a participant.
#pragma once

#include <string>

#include "geometry_msgs/msg/PoseWithCovarianceStamped.h"
#include "nav_msgs/msg/Odometry.h"
#include "pose_tracker.hpp"
#include "sensor_msgs/msg/LaserScan.h"
#include "session_scan.hpp"
#include "structloc_msgs/msg/LocalisationStatus.h"
#include "structloc_msgs/msg/ScanFeatures.h"
#include "tf2_msgs/msg/TFMessage.h"
#include "topics.hpp"

namespace structloc::localisation {

// The ranges stay owned by the message.
ScanInput FromLaserScan(const sensor_msgs::msg::LaserScan& msg);
// The scan with a copy of its ranges, to wait in a TrackingSession.
SessionScan ToSessionScan(const sensor_msgs::msg::LaserScan& msg);
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
    const TrackedPose& pose, const dds::FrameIds& frames);
tf2_msgs::msg::TFMessage ToMapToOdomTf(const geometry::Pose2D& map_to_odom, double stamp,
                                       const dds::FrameIds& frames);
structloc_msgs::msg::ScanFeatures ToScanFeatures(const LocalisationResult& result, double stamp,
                                                 const dds::FrameIds& frames);
structloc_msgs::msg::LocalisationStatus ToStatus(const LocalisationResult& result,
                                                 const TrackerStats& stats, uint64_t dropped,
                                                 double stamp, const dds::FrameIds& frames);

}  // namespace structloc::localisation
