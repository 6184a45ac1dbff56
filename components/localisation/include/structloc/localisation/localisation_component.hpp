// The localisation component: converts and moves messages around the DDS-free
// localisation_core::TrackingSession (tracking_session.hpp) and
// StartUpPolicy (start_up_policy.hpp), which hold the policies; the searches
// the start-up policy asks for run on a thread of their own. DDS listener
// threads only copy scans, odometry and initial poses into the session's inbox
// and notify; a worker thread takes them, runs the session (one scan slot: the
// newest scan wins) and publishes the pose, the map -> odom transform, the
// features and its status outside any lock a listener takes. The main thread
// saves the pose when the session says it is due and publishes diagnostics.
#pragma once

#include <atomic>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "geometry_msgs/msg/PoseArrayPubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "std_msgs/msg/EmptyPubSubTypes.h"
#include "structloc/dds_common/component_runtime.hpp"
#include "structloc/dds_common/diagnostics.hpp"
#include "structloc/localisation/pose_saver.hpp"
#include "structloc/localisation/pose_state_file.hpp"
#include "structloc/localisation_core/start_up/start_up_policy.hpp"
#include "structloc/localisation_core/tracking/session_inbox.hpp"
#include "structloc/localisation_core/tracking/tracking_session.hpp"
#include "structloc/process/cpu_wake_latency.hpp"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"
#include "structloc_msgs/msg/ScanFeaturesPubSubTypes.h"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

namespace structloc::localisation {

struct LocalisationComponentOptions {
  std::string state_file;                        // saved pose ("" = none)
  std::optional<geometry::Pose2D> initial_pose;  // from the command line
  dds_common::FrameIds frames;                   // stamped into every output
  // While it runs, no CPU of the machine takes longer than this to wake
  // (process::CpuWakeLatencyLimit; none = the platform's power management).
  std::optional<int> max_cpu_wake_latency_us;
};

class LocalisationComponent : public dds_common::Component {
 public:
  LocalisationComponent(dds_common::Node& node, std::unique_ptr<world_model::WorldModel> world,
                        const localisation_core::LocaliserOptions& localiser_options,
                        const localisation_core::SessionOptions& session_options,
                        const LocalisationComponentOptions& options);
  ~LocalisationComponent() override;
  void Step() override;
  void Stop() override;
  // A pose on rt/initialpose: this component's subscription hands it here, and
  // so does the start-up for one that came while it waited for the first scan.
  void OfferInitialPose(const geometry_msgs::msg::PoseWithCovarianceStamped& m);

 private:
  void Worker();
  void PublishDiagnostics(double now);
  void Log(const std::string& sentence);
  // Asks for options_.max_cpu_wake_latency_us; refused, it warns and runs on.
  void HoldCpuWakeLatency();
  // Runs a search the start-up policy asked for on a thread of its own (the
  // worker keeps taking scans and odometry meanwhile).
  void Launch(std::optional<localisation_core::StartUpSearch> search);
  // A finished search's answer, handed back to the start-up policy, and the
  // hypotheses it left for the worker to publish.
  void TakeBack(double now);

  LocalisationComponentOptions options_;
  std::unique_ptr<world_model::WorldModel> world_;
  dds_common::TopicWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType> pose_;
  dds_common::TopicWriter<tf2_msgs::msg::TFMessagePubSubType> tf_;
  dds_common::TopicWriter<structloc_msgs::msg::ScanFeaturesPubSubType> features_;
  dds_common::TopicWriter<structloc_msgs::msg::LocalisationStatusPubSubType> status_;
  dds_common::TopicWriter<geometry_msgs::msg::PoseArrayPubSubType> hypotheses_;
  dds_common::TopicWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType> diagnostics_;
  const dds_common::Node& node_;
  const double started_s_;

  localisation_core::SessionInbox inbox_;  // listeners -> worker; its own lock
  // Made before the session and the start-up policy, which build the map's
  // search fields (seconds for a large building), so that an operator's pose
  // sent meanwhile is not lost; its listener touches the inbox only.
  dds_common::Subscription initial_pose_subscription_;
  std::mutex session_mutex_;  // the worker (updates) and the main thread (diagnostics, saving)
  localisation_core::TrackingSession session_;
  // How the robot gets a pose and gets it back: the global search, pose
  // hints, the kidnap watch.
  localisation_core::StartUpPolicy start_up_;
  std::atomic<bool> relocalise_requested_{false};
  // The search under way (its answer is the start-up policy's to apply;
  // meanwhile the worker only asks the policy what needs no search).
  std::future<localisation_core::StartUpSearch> search_;
  // The hypotheses held after a global attempt, for the worker to publish
  // outside the lock.
  struct StartUpMessages {
    geometry_msgs::msg::PoseArray poses;
    structloc_msgs::msg::LocalisationStatus status;
  };
  std::optional<StartUpMessages> start_up_out_;
  double last_diagnostics_s_ = 0.0;
  std::string last_logged_state_;          // the diagnostics headline last printed
  std::unique_ptr<PoseSaver> pose_saver_;  // with a state file
  std::unique_ptr<process::CpuWakeLatencyLimit> wake_limit_;  // when asked for and granted
  std::string wake_limit_refused_;                            // why not, when refused
  std::thread worker_;
  // Last: destroyed first, so no sample reaches the members above then.
  dds_common::Subscription scan_subscription_;
  dds_common::Subscription odometry_subscription_;
  dds_common::Subscription relocalise_subscription_;
};

}  // namespace structloc::localisation
