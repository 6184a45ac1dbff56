// Localisation component (see header).
#include "localisation_component.hpp"

#include <iostream>

#include "diagnostics.hpp"
#include "localisation_conversions.hpp"
#include "ros_conversions.hpp"

namespace structloc::localisation {

LocalisationComponent::LocalisationComponent(dds::Node& node,
                                             std::unique_ptr<world::WorldModel> world,
                                             const LocaliserOptions& localiser_options,
                                             const LocalisationComponentOptions& options)
    : options_(options),
      world_(std::move(world)),
      pose_(node.CreateWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
          dds::topics::kPose)),
      tf_(node.CreateWriter<tf2_msgs::msg::TFMessagePubSubType>(dds::topics::kTf)),
      features_(
          node.CreateWriter<structloc_msgs::msg::ScanFeaturesPubSubType>(dds::topics::kFeatures)),
      status_(node.CreateWriter<structloc_msgs::msg::LocalisationStatusPubSubType>(
          dds::topics::kStatus)),
      diagnostics_(node.CreateWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
          dds::topics::kDiagnostics)),
      node_(node),
      started_s_(dds::WallClockSeconds()),
      tracker_(*world_, localiser_options, TrackerOptions{}) {
  const Eigen::Matrix3d initial_cov = TrackerOptions{}.InitialCovariance();
  if (options_.initial_pose) {
    pending_initial_pose_ = {{*options_.initial_pose, initial_cov}};
    std::cout << "localisation: initial pose from the command line" << std::endl;
  } else if (!options_.state_file.empty()) {
    std::optional<SavedPose> saved;
    try {
      saved = LoadSavedPose(options_.state_file);
    } catch (const std::exception& e) {
      // A crash can leave exactly such a file; it must not stop the start-up.
      std::cerr << "localisation: WARNING: ignoring the saved pose: " << e.what() << std::endl;
      last_problem_ = std::string("saved pose ignored: ") + e.what();
      last_problem_s_ = started_s_;
    }
    if (saved) {
      // The robot may have driven on meanwhile: never trust the saved variances
      // more than a freshly given initial pose.
      const Eigen::Vector3d variance = saved->variance.cwiseMax(initial_cov.diagonal());
      pending_correction_ = {{saved->map_to_odom, Eigen::Matrix3d(variance.asDiagonal())}};
      std::cout << "localisation: resuming from the pose saved in " << options_.state_file
                << std::endl;
    }
  }
  if (!pending_initial_pose_ && !pending_correction_) {
    std::cout << "localisation: waiting for an initial pose on " << dds::topics::kInitialPose.name
              << std::endl;
  }
  node.Subscribe<sensor_msgs::msg::LaserScanPubSubType>(
      dds::topics::kScan, [this](const sensor_msgs::msg::LaserScan& m) { OnScan(m); });
  node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
      dds::topics::kOdom, [this](const nav_msgs::msg::Odometry& m) { OnOdometry(m); });
  node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      dds::topics::kInitialPose,
      [this](const geometry_msgs::msg::PoseWithCovarianceStamped& m) { OnInitialPose(m); });
  worker_ = std::thread([this] { Worker(); });
}

LocalisationComponent::~LocalisationComponent() {
  Stop();
}

void LocalisationComponent::Stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void LocalisationComponent::OnScan(const sensor_msgs::msg::LaserScan& scan) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pending_scan_) ++dropped_;  // overload: the newest scan wins
    pending_scan_ = scan;
    new_input_ = true;
    pending_since_ = dds::WallClockSeconds();
    last_scan_wall_s_ = pending_since_;
  }
  wake_.notify_one();
}

void LocalisationComponent::OnOdometry(const nav_msgs::msg::Odometry& msg) {
  const auto odom = FromOdometry(msg);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_odometry_wall_s_ = dds::WallClockSeconds();
    if (auto r = tracker_.AddOdometry(odom.stamp, odom.pose)) {
      NoteProblem(std::string("odometry rejected: ") + ToString(*r));
      return;
    }
    std::optional<Rejection> rejected;
    if (pending_initial_pose_ && !tracker_.HasInitialPose()) {
      rejected = tracker_.SetInitialPose(odom.stamp, pending_initial_pose_->first,
                                         pending_initial_pose_->second);
      pending_initial_pose_.reset();
    }
    if (pending_correction_ && !tracker_.HasInitialPose()) {
      rejected = tracker_.SetInitialPose(odom.stamp,
                                         geometry::Compose(pending_correction_->first, odom.pose),
                                         pending_correction_->second);
      pending_correction_.reset();
    }
    if (rejected) NoteProblem(std::string("initial pose rejected: ") + ToString(*rejected));
    new_input_ = true;
  }
  wake_.notify_one();  // a waiting scan may now be covered
}

void LocalisationComponent::OnInitialPose(
    const geometry_msgs::msg::PoseWithCovarianceStamped& msg) {
  Eigen::Matrix3d cov;
  const auto p = FromPoseWithCovariance(msg, &cov);
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto r = tracker_.SetInitialPose(p.stamp, p.pose, cov)) {
    if (*r == Rejection::kNoOdometry) {
      pending_initial_pose_ = {{p.pose, cov}};  // valid: SetInitialPose checks that first
    } else {
      NoteProblem(std::string("initial pose on ") + dds::topics::kInitialPose.name +
                  " rejected: " + ToString(*r));
    }
    return;
  }
  std::cout << "localisation: initial pose set from " << dds::topics::kInitialPose.name
            << std::endl;
}

void LocalisationComponent::Worker() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    // The flag keeps a notification sent while this thread was publishing.
    wake_.wait_for(lock, std::chrono::milliseconds(20), [this] { return stopping_ || new_input_; });
    new_input_ = false;
    if (stopping_ || !pending_scan_) continue;
    const double waited = dds::WallClockSeconds() - pending_since_;
    const auto outcome = tracker_.ProcessScan(FromLaserScan(*pending_scan_), waited);
    if (outcome.verdict == PoseTracker::ScanVerdict::kWaitForOdometry) continue;
    const double stamp = dds::FromRosTime(pending_scan_->header().stamp());
    pending_scan_.reset();
    if (outcome.verdict == PoseTracker::ScanVerdict::kRejected) {
      NoteProblem(std::string("scan rejected: ") + ToString(outcome.rejection) +
                  (outcome.detail != nullptr ? std::string(": ") + outcome.detail : ""));
      continue;
    }
    const auto& r = *outcome.result;
    if (r.lost && !last_lost_) lost_since_s_ = dds::WallClockSeconds();
    last_lost_ = r.lost;
    last_lost_reason_ = r.lost ? ToString(r.lost_reason) : "";
    last_quality_ = r.quality;
    auto pose = ToPoseWithCovarianceStamped(outcome.pose);
    auto tf = ToMapToOdomTf(tracker_.MapToOdom(), stamp);
    auto features = ToScanFeatures(r, stamp);
    auto status = ToStatus(r, tracker_.Stats(), dropped_, stamp);
    // Published outside the lock: the DDS threads delivering scans and
    // odometry never wait for these writes.
    lock.unlock();
    pose_.Write(pose);
    tf_.Write(tf);
    features_.Write(features);
    status_.Write(status);
    lock.lock();
  }
}

void LocalisationComponent::Step() {
  const double now = dds::WallClockSeconds();
  std::optional<TrackedPose> latest;
  geometry::Pose2D map_to_odom;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    latest = tracker_.Latest();
    map_to_odom = tracker_.MapToOdom();
  }
  if (latest && !options_.state_file.empty() &&
      now - last_state_save_s_ >= options_.state_period_s) {
    try {
      SavePoseAtomically(options_.state_file, {map_to_odom, latest->covariance.diagonal()});
    } catch (const std::exception& e) {
      std::cerr << "localisation: " << e.what() << std::endl;
    }
    last_state_save_s_ = now;
  }
  if (now - last_diagnostics_s_ >= 0.5) PublishDiagnostics(now);
}

void LocalisationComponent::NoteProblem(const std::string& problem) {
  last_problem_ = problem;
  last_problem_s_ = dds::WallClockSeconds();
}

dds::HealthReport LocalisationComponent::Health(double now) {
  dds::HealthReport report;
  // A source silent for a while is a warning; for long, an error.
  auto silence = [&](double since, const std::string& what) {
    const double silent = now - since;
    report.level =
        silent > options_.silent_error_after_s ? dds::HealthLevel::kError : dds::HealthLevel::kWarn;
    report.message = what + " for " + std::to_string(silent).substr(0, 4) + " s";
  };
  const auto peer_problems = node_.PeerProblems();
  if (!peer_problems.empty()) {
    report.level = dds::HealthLevel::kError;
    report.message = peer_problems.front();
  } else if (last_odometry_wall_s_ == 0.0) {
    silence(started_s_, "no odometry on " + dds::topics::kOdom.name + " yet");
  } else if (!tracker_.HasInitialPose()) {
    report.level = dds::HealthLevel::kWarn;
    report.message = "no initial pose: publish one on " + dds::topics::kInitialPose.name +
                     " or pass --initial-pose";
  } else if (now - std::max(last_scan_wall_s_, started_s_) > options_.scan_timeout_s) {
    silence(std::max(last_scan_wall_s_, started_s_),
            last_scan_wall_s_ == 0.0 ? "no scans on " + dds::topics::kScan.name + " yet"
                                     : "no scans on " + dds::topics::kScan.name);
  } else if (now - last_odometry_wall_s_ > options_.scan_timeout_s) {
    silence(last_odometry_wall_s_, "no odometry on " + dds::topics::kOdom.name);
  } else if (last_lost_) {
    // Dead reckoning for a while is normal (a corridor, a crowd); for long it is not.
    report.level = now - lost_since_s_ > options_.lost_error_after_s ? dds::HealthLevel::kError
                                                                     : dds::HealthLevel::kWarn;
    report.message = "lost (dead reckoning) for " +
                     std::to_string(now - lost_since_s_).substr(0, 4) + " s: " + last_lost_reason_;
  } else {
    report.message = "localised";
  }
  return report;
}

void LocalisationComponent::PublishDiagnostics(double now) {
  last_diagnostics_s_ = now;
  std::unique_lock<std::mutex> lock(mutex_);
  dds::HealthReport report = Health(now);
  const auto& stats = tracker_.Stats();
  const bool recent_problem =
      !last_problem_.empty() && now - last_problem_s_ <= options_.problem_hold_s;
  report.values = {{"scans_processed", std::to_string(stats.scans_processed)},
                   {"scans_lost", std::to_string(stats.scans_lost)},
                   {"scans_dropped", std::to_string(dropped_)},
                   {"scans_rejected", std::to_string(stats.Rejected())},
                   {"scans_not_deskewed", std::to_string(stats.scans_not_deskewed)},
                   {"quality", std::to_string(last_quality_)},
                   {"last_problem", recent_problem ? last_problem_ : ""},
                   {"last_problem_age_s",
                    recent_problem ? std::to_string(now - last_problem_s_).substr(0, 4) : ""}};
  for (size_t i = 0; i < stats.rejected.size(); ++i) {
    if (stats.rejected[i] > 0) {
      report.values.emplace_back(std::string("rejected: ") + ToString(static_cast<Rejection>(i)),
                                 std::to_string(stats.rejected[i]));
    }
  }
  for (const auto& problem : node_.PeerProblems()) report.values.emplace_back("peer", problem);
  // A log line whenever the headline changes kind (not its running seconds).
  const std::string state = std::to_string(static_cast<int>(report.level)) + " " +
                            report.message.substr(0, report.message.find(" for "));
  if (state != last_logged_state_) {
    last_logged_state_ = state;
    std::cout << "localisation: " << dds::ToString(report.level) << " " << report.message
              << std::endl;
  }
  const auto diag = dds::ToDiagnosticArray("localisation", report, now);
  lock.unlock();
  diagnostics_.Write(diag);
}

}  // namespace structloc::localisation
