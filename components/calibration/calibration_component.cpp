// Calibration component (see header).
#include "calibration_component.hpp"

#include "diagnostics.hpp"

namespace structloc::calibration {

CalibrationComponent::CalibrationComponent(dds::Node& node)
    : result_(node.CreateWriter<structloc_msgs::msg::CalibrationResultPubSubType>(
          dds::topics::kCalibration)),
      diagnostics_(node.CreateWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
          dds::topics::kDiagnostics)) {
  node.Subscribe<structloc_msgs::msg::WheelEncodersPubSubType>(
      dds::topics::kWheelEncoders,
      [this](const structloc_msgs::msg::WheelEncoders&) { ++encoder_samples_; });
  node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      dds::topics::kPose,
      [this](const geometry_msgs::msg::PoseWithCovarianceStamped&) { ++fixes_; });
}

void CalibrationComponent::Step() {
  dds::HealthReport report;
  report.message = "recording";
  report.values = {{"encoder_samples", std::to_string(encoder_samples_.load())},
                   {"fixes", std::to_string(fixes_.load())}};
  auto diag = dds::ToDiagnosticArray("calibration", report, dds::WallClockSeconds());
  diagnostics_.Write(diag);
}

}  // namespace structloc::calibration
