// Localisation component (see header).
#include "structloc/localisation/localisation_component.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <iomanip>
#include <iostream>

#include "structloc/dds_common/diagnostics.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/localisation/localisation_conversions.hpp"

namespace structloc::localisation {

LocalisationComponent::LocalisationComponent(
    dds_common::Node& node, std::unique_ptr<world_model::WorldModel> world,
    const localisation_core::LocaliserOptions& localiser_options,
    const localisation_core::SessionOptions& session_options,
    const LocalisationComponentOptions& options)
    : options_(options),
      world_(std::move(world)),
      pose_(node.CreateWriter<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
          dds_common::topics::kPose)),
      tf_(node.CreateWriter<tf2_msgs::msg::TFMessagePubSubType>(dds_common::topics::kTf)),
      features_(node.CreateWriter<structloc_msgs::msg::ScanFeaturesPubSubType>(
          dds_common::topics::kFeatures)),
      status_(node.CreateWriter<structloc_msgs::msg::LocalisationStatusPubSubType>(
          dds_common::topics::kStatus)),
      hypotheses_(node.CreateWriter<geometry_msgs::msg::PoseArrayPubSubType>(
          dds_common::topics::kHypotheses)),
      diagnostics_(node.CreateWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
          dds_common::topics::kDiagnostics)),
      node_(node),
      started_s_(dds_common::WallClockSeconds()),
      initial_pose_subscription_(
          node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
              dds_common::topics::kInitialPose,
              [this](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
                OfferInitialPose(m);
              })),
      session_(world_.get(), localiser_options, session_options,
               localisation_core::Scheduling::kNewestWins),
      start_up_(world_.get(), localiser_options.sensor_mount, session_options, {}) {
  if (world_ && !start_up_.CanSearch()) {
    std::cerr << "localisation: WARNING: the map cannot be searched (" << start_up_.NoSearchReason()
              << "): give the robot a pose; a kidnapped robot is not found again" << std::endl;
  }
  if (options_.initial_pose) {
    Log(start_up_.GivenAtStart(
        session_, *options_.initial_pose,
        localisation_core::TrackingSession::InitialPoseWhen::kAtFirstOdometry,
        "the initial pose from the command line"));
  }
  if (!options_.initial_pose && !options_.state_file.empty()) {
    try {
      if (const auto saved = LoadSavedPose(options_.state_file)) {
        Log(start_up_.Resume(session_, {saved->map_to_odom, saved->variance},
                             "the pose saved in " + options_.state_file));
      }
    } catch (const std::exception& e) {
      // A crash can leave exactly such a file; it must not stop the start-up.
      std::cerr << "localisation: WARNING: ignoring the saved pose: " << e.what() << std::endl;
      session_.NoteProblem(std::string("saved pose ignored: ") + e.what(), started_s_);
    }
  }
  if (!options_.state_file.empty()) pose_saver_ = std::make_unique<PoseSaver>(options_.state_file);
  HoldCpuWakeLatency();
  if (const auto waiting =
          start_up_.WaitingSentence(session_, dds_common::topics::kInitialPose.name)) {
    Log(*waiting);
  }
  // The listeners only copy into the inbox and notify.
  scan_subscription_ = node.Subscribe<sensor_msgs::msg::LaserScanPubSubType>(
      dds_common::topics::kScan, [this](const sensor_msgs::msg::LaserScan& m) {
        auto scan = ToSessionScan(m);
        scan.TakenEarlier(session_.Options().scan_latency_s);
        inbox_.OfferScan(std::move(scan), dds_common::WallClockSeconds());
      });
  odometry_subscription_ = node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
      dds_common::topics::kOdom, [this](const nav_msgs::msg::Odometry& m) {
        const auto odom = FromOdometry(m);
        inbox_.OfferOdometry(odom.stamp, odom.pose, dds_common::WallClockSeconds());
      });
  relocalise_subscription_ = node.Subscribe<std_msgs::msg::EmptyPubSubType>(
      dds_common::topics::kReinitializeGlobalLocalization,
      [this](const std_msgs::msg::Empty&) { relocalise_requested_ = true; });
  // Started last: if a subscription above throws, no thread is left running.
  worker_ = std::thread([this] { Worker(); });
}

LocalisationComponent::~LocalisationComponent() {
  Stop();
}

void LocalisationComponent::OfferInitialPose(
    const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
  localisation_core::InitialPoseInput in;
  const auto p = FromPoseWithCovariance(m, &in.covariance);
  in.stamp = p.stamp;
  in.pose = p.pose;
  inbox_.OfferInitialPose(in);
}

void LocalisationComponent::HoldCpuWakeLatency() {
  if (!options_.max_cpu_wake_latency_us) return;
  const int max_us = *options_.max_cpu_wake_latency_us;
  try {
    wake_limit_ = std::make_unique<process::CpuWakeLatencyLimit>(max_us);
    Log("every CPU of this machine is held to wake within " + std::to_string(max_us) +
        " us while the localisation runs (lower latency, more power)");
  } catch (const std::exception& e) {
    // A faster wake-up is worth having, not worth refusing to localise for.
    wake_limit_refused_ = e.what();
    std::cerr << "localisation: WARNING: " << e.what() << "; running without the limit"
              << std::endl;
    session_.NoteProblem(e.what(), started_s_);
  }
}

void LocalisationComponent::Log(const std::string& sentence) {
  std::cout << "localisation: " << sentence << std::endl;
}

void LocalisationComponent::Launch(std::optional<localisation_core::StartUpSearch> search) {
  if (!search) return;
  search_ = std::async(std::launch::async, [this, search = std::move(*search)]() mutable {
    start_up_.Run(search);
    return std::move(search);
  });
}

void LocalisationComponent::TakeBack(double now) {
  if (!search_.valid() || search_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return;
  const localisation_core::StartUpSearch search = search_.get();
  const auto outcome = start_up_.Apply(session_, search, now);
  for (const auto& sentence : outcome.log) Log(sentence);
  if (!outcome.outdated && search.kind == localisation_core::StartUpSearch::Kind::kGlobal &&
      search.global && !outcome.pose_set) {
    const double stamp = search.Stamp();
    start_up_out_ = StartUpMessages{ToPoseArray(outcome.hypotheses, stamp, options_.frames),
                                    ToStartUpStatus(outcome.hypotheses, stamp, options_.frames)};
  }
}

void LocalisationComponent::Stop() {
  inbox_.Stop();
  if (worker_.joinable()) worker_.join();
  if (search_.valid()) search_.wait();  // it uses start_up_
}

void LocalisationComponent::Worker() {
  localisation_core::SessionInputs inputs;
  while (inbox_.WaitAndTake(std::chrono::milliseconds(20), inputs)) {
    const double now = dds_common::WallClockSeconds();
    if (inputs.scan_arrived_s == 0.0) inputs.scan_arrived_s = now;
    geometry_msgs::msg::PoseWithCovarianceStamped pose;
    tf2_msgs::msg::TFMessage tf;
    structloc_msgs::msg::ScanFeatures features;
    structloc_msgs::msg::LocalisationStatus status;
    std::optional<localisation_core::ScanReport> report;
    std::optional<StartUpMessages> start_up;
    bool tracked = false;
    {
      std::lock_guard<std::mutex> lock(session_mutex_);
      TakeBack(now);
      if (relocalise_requested_.exchange(false)) {
        if (const auto sentence = start_up_.Relocalise(
                session_, dds_common::topics::kReinitializeGlobalLocalization.name)) {
          Log(*sentence);
        }
      }
      std::optional<localisation_core::SessionScan> scan = std::move(inputs.scan);
      inputs.scan.reset();
      if (session_.Apply(inputs, dds_common::topics::kInitialPose.name) > 0)
        Log(start_up_.GivenOnTopic(session_, dds_common::topics::kInitialPose.name));
      start_up_.Tend(session_);
      if (scan && !search_.valid()) Launch(start_up_.SearchAt(session_, *scan));
      if (scan) session_.AddScan(std::move(*scan), inputs.scan_arrived_s);
      start_up.swap(start_up_out_);
      report = session_.Next(now);
      tracked = report && report->kind == localisation_core::ScanReport::Kind::kTracked;
      if (tracked && report->reacquired) {
        const auto& p = report->pose.pose;
        std::cout << "localisation: re-acquired at t=" << report->stamp << " s: (" << p.x << ", "
                  << p.y << ", " << p.theta << "), a jump of (" << report->jump.x << ", "
                  << report->jump.y << ", " << report->jump.theta << ")" << std::endl;
      }
      if (tracked) {
        pose = ToPoseWithCovarianceStamped(report->pose, options_.frames);
        tf = ToMapToOdomTf(session_.Tracker()->MapToOdom(), report->stamp, options_.frames);
      }
    }
    if (start_up) {
      hypotheses_.Write(start_up->poses);
      status_.Write(start_up->status);
    }
    if (!tracked) continue;
    // Published outside every lock: neither the DDS threads delivering scans
    // and odometry nor the main thread wait for these writes. The pose first:
    // the features and the status are made after it is out.
    pose_.Write(pose);
    tf_.Write(tf);
    {
      std::lock_guard<std::mutex> lock(session_mutex_);
      const auto& r = *report->result;
      features = ToScanFeatures(r, report->stamp, options_.frames);
      status = ToStatus(r, report->lost ? report->lost_reason : "", session_.Stats(),
                        session_.Dropped(), report->stamp, options_.frames);
    }
    features_.Write(features);
    status_.Write(status);
    std::lock_guard<std::mutex> lock(session_mutex_);
    session_.Anticipate();
    std::vector<std::string> sentences;
    Launch(start_up_.Watch(session_, *report, sentences));
    for (const auto& sentence : sentences) Log(sentence);
  }
}

void LocalisationComponent::Step() {
  const double now = dds_common::WallClockSeconds();
  if (pose_saver_) {
    std::optional<localisation_core::SessionState> state;
    {
      std::lock_guard<std::mutex> lock(session_mutex_);
      state = session_.StateToSave(now);
    }
    if (state) pose_saver_->Save({state->map_to_odom, state->variance});
  }
  if (now - last_diagnostics_s_ >= 0.5) PublishDiagnostics(now);
}

void LocalisationComponent::PublishDiagnostics(double now) {
  last_diagnostics_s_ = now;
  localisation_core::HealthInputs in;
  in.now_s = now;
  in.started_s = started_s_;
  in.last_scan_s = inbox_.LastScanArrival();
  in.last_odometry_s = inbox_.LastOdometryArrival();
  in.peer_problems = node_.PeerProblems();
  in.scan_topic = dds_common::topics::kScan.name;
  in.odometry_topic = dds_common::topics::kOdom.name;
  in.initial_pose_topic = dds_common::topics::kInitialPose.name;
  dds_common::HealthReport report;
  std::string start_up;
  size_t kidnappings = 0;
  {
    std::lock_guard<std::mutex> lock(session_mutex_);
    report = ToHealthReport(localisation_core::AssessHealth(session_, in));
    kidnappings = start_up_.Kidnappings();
    start_up = start_up_.State(session_);
  }
  if (const uint64_t overflow = inbox_.OdometryOverflow()) {
    report.values.emplace_back("odometry_dropped", std::to_string(overflow));
  }
  for (const auto& peer : node_.PeerProblems()) report.values.emplace_back("peer", peer);
  report.values.emplace_back("start_up", start_up);
  report.values.emplace_back("kidnappings", std::to_string(kidnappings));
  report.values.emplace_back(
      "cpu_wake_latency",
      wake_limit_
          ? "at most " + std::to_string(wake_limit_->MaxUs()) + " us"
          : "not limited" + (wake_limit_refused_.empty() ? "" : ": " + wake_limit_refused_));
  // A log line whenever the headline changes kind (not its running seconds).
  const std::string state = std::to_string(static_cast<int>(report.level)) + " " +
                            report.message.substr(0, report.message.find(" for "));
  if (state != last_logged_state_) {
    last_logged_state_ = state;
    std::cout << "localisation: " << dds_common::ToString(report.level) << " " << report.message
              << std::endl;
  }
  diagnostics_.Write(dds_common::ToDiagnosticArray("localisation", report, now));
}

}  // namespace structloc::localisation
