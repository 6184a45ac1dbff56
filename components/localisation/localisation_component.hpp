// The localisation component: subscribes scans, odometry and initial poses,
// publishes pose, tf, features, status and diagnostics. The pipeline itself
// lives in the DDS-free localisation core (issue 3); this adapter only moves data.
#pragma once

#include <atomic>
#include <cstdint>

#include "component_runtime.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"
#include "structloc_msgs/msg/ScanFeaturesPubSubTypes.h"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

namespace structloc::localisation {

struct LocalisationComponentOptions {
  double scan_timeout_s = 0.5;  // diagnostics go WARN when no scan arrived for this long
};

class LocalisationComponent : public dds::Component {
 public:
  LocalisationComponent(dds::Node& node, const LocalisationComponentOptions& options);
  void Step() override;

 private:
  LocalisationComponentOptions options_;
  dds::TopicWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType> pose_;
  dds::TopicWriter<tf2_msgs::msg::TFMessagePubSubType> tf_;
  dds::TopicWriter<structloc_msgs::msg::ScanFeaturesPubSubType> features_;
  dds::TopicWriter<structloc_msgs::msg::LocalisationStatusPubSubType> status_;
  dds::TopicWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType> diagnostics_;
  std::atomic<uint64_t> scans_{0};
  std::atomic<uint64_t> odoms_{0};
  std::atomic<uint64_t> initial_poses_{0};
  std::atomic<double> last_scan_wall_s_{0.0};
};

}  // namespace structloc::localisation
