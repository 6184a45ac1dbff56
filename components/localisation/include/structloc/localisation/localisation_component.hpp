// The localisation component: converts and moves messages around the DDS-free
// localisation_core::TrackingSession (tracking_session.hpp), which holds the policy. DDS listener
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
#include "structloc/localisation_core/global/global_start.hpp"
#include "structloc/localisation_core/global/kidnap_watch.hpp"
#include "structloc/localisation_core/global/pose_hint_check.hpp"
#include "structloc/localisation_core/tracking/session_inbox.hpp"
#include "structloc/localisation_core/tracking/tracking_session.hpp"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"
#include "structloc_msgs/msg/ScanFeaturesPubSubTypes.h"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

namespace structloc::localisation {

struct LocalisationComponentOptions {
  std::string state_file;                        // saved pose ("" = none)
  std::optional<geometry::Pose2D> initial_pose;  // from the command line
  dds_common::FrameIds frames;                   // stamped into every output
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

 private:
  void Worker();
  void PublishDiagnostics(double now);
  // What a search for a robot without a pose found, for the worker to apply.
  struct SearchAnswer {
    uint64_t generation = 0;  // search_generation_ when it started
    double stamp = 0.0;       // of the scan searched
    std::optional<localisation_core::GlobalStart::Attempt> global;
    std::optional<localisation_core::PoseHintCheck::Outcome> hint;
    std::optional<localisation_core::PoseHintCheck> hint_check;  // after the check
    // A search for a tracked robot that may have been carried away: the
    // pose tracked at the scan and the scan's laser-frame points.
    std::optional<geometry::Pose2D> tracked;
    std::vector<Eigen::Vector2d> points;
  };
  // Without a pose, at a scan: starts a search on a thread of its own (the
  // worker keeps taking scans and odometry meanwhile) when none is running:
  // the pose hint checked by a local search around it, else the scan against
  // the whole map.
  void StartSearch(const localisation_core::SessionScan& scan);
  // A finished search's answer, applied when nothing it was started for has
  // changed since (a pose given, a relocalisation asked for).
  void ApplySearch(const SearchAnswer& answer, double now);
  void ApplyGlobal(const localisation_core::GlobalStart::Attempt& attempt, double stamp,
                   double now);
  void ApplyHint(const localisation_core::PoseHintCheck::Outcome& outcome, double now);
  // After a tracked scan: the kidnap watch, and its search when one is due.
  void WatchForKidnapping(const localisation_core::ScanReport& report);
  void ApplyKidnapSearch(const SearchAnswer& answer, double now);
  void EndKidnapDoubt();
  // A given pose that just started tracking, taken back as a hint.
  void TakeBackAsHint();

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
  std::mutex session_mutex_;  // the worker (updates) and the main thread (diagnostics, saving)
  localisation_core::TrackingSession session_;
  // Locates a robot without a pose (none given, none saved, or asked to).
  std::unique_ptr<localisation_core::GlobalStart> global_;
  // Where a pose given on the command line or rt/initialpose came from, until
  // the session has started tracking from it and it is taken back as a hint
  // (empty: none waiting).
  std::string given_pose_source_;
  // A hint until it is confirmed, or given up on.
  std::optional<localisation_core::PoseHintCheck> pose_hint_check_;
  localisation_core::PoseHintCheckOptions hint_check_options_;
  std::atomic<bool> relocalise_requested_{false};
  // The search under way (global_ and a copy of the hint check are its own
  // until it ends; the worker then only reads global_->Localiser(), whose
  // const methods change nothing, for the kidnap watch), and the generation
  // that outdates its answer.
  std::future<SearchAnswer> search_;
  uint64_t search_generation_ = 0;
  bool forget_recent_scans_ = false;  // once no search uses global_
  // Hypotheses held after the last global attempt applied (diagnostics), and
  // the messages saying so, for the worker to publish outside the lock.
  size_t held_hypotheses_ = 0;
  struct StartUpMessages {
    geometry_msgs::msg::PoseArray poses;
    structloc_msgs::msg::LocalisationStatus status;
  };
  std::optional<StartUpMessages> start_up_out_;
  // Whether the tracked robot was carried away (with global_); in doubt, and
  // hypotheses held by its searches (searched again at every scan).
  std::unique_ptr<localisation_core::KidnapWatch> kidnap_watch_;
  bool kidnap_doubt_ = false;
  size_t kidnap_hypotheses_ = 0;
  size_t kidnappings_ = 0;
  double last_diagnostics_s_ = 0.0;
  std::string last_logged_state_;          // the diagnostics headline last printed
  std::unique_ptr<PoseSaver> pose_saver_;  // with a state file
  std::thread worker_;
  // Last: destroyed first, so no sample reaches the members above then.
  dds_common::Subscription scan_subscription_;
  dds_common::Subscription odometry_subscription_;
  dds_common::Subscription initial_pose_subscription_;
  dds_common::Subscription relocalise_subscription_;
};

}  // namespace structloc::localisation
