// Localisation component (see header).
#include "localisation_component.hpp"

#include "diagnostics.hpp"

namespace structloc::localisation {

LocalisationComponent::LocalisationComponent(dds::Node& node,
                                             const LocalisationComponentOptions& options)
    : options_(options),
      pose_(node.CreateWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
          dds::topics::kPose)),
      tf_(node.CreateWriter<tf2_msgs::msg::TFMessagePubSubType>(dds::topics::kTf)),
      features_(
          node.CreateWriter<structloc_msgs::msg::ScanFeaturesPubSubType>(dds::topics::kFeatures)),
      status_(node.CreateWriter<structloc_msgs::msg::LocalisationStatusPubSubType>(
          dds::topics::kStatus)),
      diagnostics_(node.CreateWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
          dds::topics::kDiagnostics)) {
  node.Subscribe<sensor_msgs::msg::LaserScanPubSubType>(
      dds::topics::kScan, [this](const sensor_msgs::msg::LaserScan&) {
        ++scans_;
        last_scan_wall_s_ = dds::WallClockSeconds();
      });
  node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
      dds::topics::kOdom, [this](const nav_msgs::msg::Odometry&) { ++odoms_; });
  node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      dds::topics::kInitialPose,
      [this](const geometry_msgs::msg::PoseWithCovarianceStamped&) { ++initial_poses_; });
}

void LocalisationComponent::Step() {
  const double now = dds::WallClockSeconds();
  dds::HealthReport report;
  if (now - last_scan_wall_s_ > options_.scan_timeout_s) {
    report.level = dds::HealthLevel::kWarn;
    report.message = "no scans for " + std::to_string(options_.scan_timeout_s) + " s";
  } else {
    report.message = "receiving scans";
  }
  report.values = {{"scans_received", std::to_string(scans_.load())},
                   {"odom_received", std::to_string(odoms_.load())},
                   {"initial_poses_received", std::to_string(initial_poses_.load())}};
  auto diag = dds::ToDiagnosticArray("localisation", report, now);
  diagnostics_.Write(diag);
}

}  // namespace structloc::localisation
