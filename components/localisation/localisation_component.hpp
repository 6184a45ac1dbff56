// The localisation component: subscribes scans, odometry and initial poses,
// runs the DDS-free PoseTracker on a worker thread (one scan slot: the newest
// scan wins, dropped ones are counted) and publishes the pose, the map -> odom
// transform, the features, its status and diagnostics. It saves its pose
// every few seconds and resumes from it after a restart.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "component_runtime.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "diagnostics.hpp"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "pose_state_file.hpp"
#include "pose_tracker.hpp"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"
#include "structloc_msgs/msg/ScanFeaturesPubSubTypes.h"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

namespace structloc::localisation {

struct LocalisationComponentOptions {
  double scan_timeout_s = 0.5;  // diagnostics go WARN without scans (or odometry) for this long
  double silent_error_after_s = 5.0;  // ... and ERROR when a source stays silent this long
  double problem_hold_s = 10.0;       // a rejected input is reported in diagnostics this long
  std::string state_file;             // saved pose ("" = none)
  double state_period_s = 2.0;        // how often the pose is saved
  double lost_error_after_s = 5.0;    // diagnostics go from WARN to ERROR when lost this long
  std::optional<geometry::Pose2D> initial_pose;  // from the command line
};

class LocalisationComponent : public dds::Component {
 public:
  LocalisationComponent(dds::Node& node, std::unique_ptr<world::WorldModel> world,
                        const LocaliserOptions& localiser_options,
                        const LocalisationComponentOptions& options);
  ~LocalisationComponent() override;
  void Step() override;
  void Stop() override;

 private:
  void OnScan(const sensor_msgs::msg::LaserScan& scan);
  void OnOdometry(const nav_msgs::msg::Odometry& odom);
  void OnInitialPose(const geometry_msgs::msg::PoseWithCovarianceStamped& pose);
  void Worker();
  void Process(const sensor_msgs::msg::LaserScan& scan, double waited_s);
  void PublishDiagnostics(double now);
  void NoteProblem(const std::string& problem);  // caller holds mutex_
  dds::HealthReport Health(double now);          // caller holds mutex_

  LocalisationComponentOptions options_;
  std::unique_ptr<world::WorldModel> world_;
  dds::TopicWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType> pose_;
  dds::TopicWriter<tf2_msgs::msg::TFMessagePubSubType> tf_;
  dds::TopicWriter<structloc_msgs::msg::ScanFeaturesPubSubType> features_;
  dds::TopicWriter<structloc_msgs::msg::LocalisationStatusPubSubType> status_;
  dds::TopicWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType> diagnostics_;
  const dds::Node& node_;
  const double started_s_;

  std::mutex mutex_;  // guards everything below
  std::condition_variable wake_;
  PoseTracker tracker_;
  std::optional<sensor_msgs::msg::LaserScan> pending_scan_;
  bool new_input_ = false;  // a scan or odometry arrived since the worker last looked
  double pending_since_ = 0.0;
  std::optional<std::pair<geometry::Pose2D, Eigen::Matrix3d>> pending_initial_pose_;
  // A saved map -> odom correction to resume from at the first odometry sample.
  std::optional<std::pair<geometry::Pose2D, Eigen::Matrix3d>> pending_correction_;
  uint64_t dropped_ = 0;
  bool stopping_ = false;
  double last_scan_wall_s_ = 0.0;      // 0: none yet
  double last_odometry_wall_s_ = 0.0;  // 0: none yet
  double last_state_save_s_ = 0.0;
  double last_diagnostics_s_ = 0.0;
  bool last_lost_ = false;
  double lost_since_s_ = 0.0;
  std::string last_lost_reason_;
  double last_quality_ = 0.0;
  std::string last_problem_;  // newest rejected input, for diagnostics
  double last_problem_s_ = 0.0;
  std::string last_logged_state_;  // the diagnostics headline last printed
  std::thread worker_;
};

}  // namespace structloc::localisation
