// The odometry-calibration component: records wheel encoders and position
// fixes from DDS and publishes calibration results (latched). The estimation
// core comes with issue 6; this adapter already receives and reports.
#pragma once

#include <atomic>
#include <cstdint>

#include "component_runtime.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "structloc_msgs/msg/CalibrationResultPubSubTypes.h"
#include "structloc_msgs/msg/WheelEncodersPubSubTypes.h"

namespace structloc::calibration {

class CalibrationComponent : public dds::Component {
 public:
  explicit CalibrationComponent(dds::Node& node);
  void Step() override;

 private:
  dds::TopicWriter<structloc_msgs::msg::CalibrationResultPubSubType> result_;
  dds::TopicWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType> diagnostics_;
  std::atomic<uint64_t> encoder_samples_{0};
  std::atomic<uint64_t> fixes_{0};
};

}  // namespace structloc::calibration
