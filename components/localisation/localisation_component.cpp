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
      session_(world_.get(), localiser_options, session_options,
               localisation_core::Scheduling::kNewestWins) {
  if (world_) {
    global_ = std::make_unique<localisation_core::GlobalStart>(
        *world_, localiser_options.sensor_mount, session_options.tracker.InitialCovariance());
    kidnap_watch_ = std::make_unique<localisation_core::KidnapWatch>(
        global_->Localiser(), localiser_options.sensor_mount);
  }
  hint_check_options_.radius_m = session_options.tracker.reacquire_max_radius_m;
  hint_check_options_.max_radius_m =
      std::max(hint_check_options_.max_radius_m, hint_check_options_.radius_m);
  if (options_.initial_pose) {
    session_.ExpectInitialPose(
        *options_.initial_pose,
        localisation_core::TrackingSession::InitialPoseWhen::kAtFirstOdometry);
    if (global_) given_pose_source_ = "the initial pose from the command line";
    std::cout << "localisation: initial pose from the command line"
              << (global_ ? ", for the first odometry; a search around it confirms it" : "")
              << std::endl;
  }
  if (!options_.initial_pose && !options_.state_file.empty()) {
    try {
      if (const auto saved = LoadSavedPose(options_.state_file)) {
        const localisation_core::SessionState state{saved->map_to_odom, saved->variance};
        if (global_) {
          pose_hint_check_.emplace(state, "the pose saved in " + options_.state_file,
                                   hint_check_options_);
          std::cout << "localisation: resuming from the pose saved in " << options_.state_file
                    << " once a search around it confirms it" << std::endl;
        } else {
          session_.ResumeFrom(state);
          std::cout << "localisation: resuming from the pose saved in " << options_.state_file
                    << std::endl;
        }
      }
    } catch (const std::exception& e) {
      // A crash can leave exactly such a file; it must not stop the start-up.
      std::cerr << "localisation: WARNING: ignoring the saved pose: " << e.what() << std::endl;
      session_.NoteProblem(std::string("saved pose ignored: ") + e.what(), started_s_);
    }
  }
  if (!options_.state_file.empty()) pose_saver_ = std::make_unique<PoseSaver>(options_.state_file);
  if (session_.WaitingForInitialPose() && !pose_hint_check_) {
    std::cout << "localisation: no initial pose: locating the robot globally from the scans "
              << "until one pose explains a scan without a doubt (or one comes on "
              << dds_common::topics::kInitialPose.name << ")" << std::endl;
  }
  // The listeners only copy into the inbox and notify.
  scan_subscription_ = node.Subscribe<sensor_msgs::msg::LaserScanPubSubType>(
      dds_common::topics::kScan, [this](const sensor_msgs::msg::LaserScan& m) {
        inbox_.OfferScan(ToSessionScan(m), dds_common::WallClockSeconds());
      });
  odometry_subscription_ = node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
      dds_common::topics::kOdom, [this](const nav_msgs::msg::Odometry& m) {
        const auto odom = FromOdometry(m);
        inbox_.OfferOdometry(odom.stamp, odom.pose, dds_common::WallClockSeconds());
      });
  initial_pose_subscription_ =
      node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
          dds_common::topics::kInitialPose,
          [this](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
            localisation_core::InitialPoseInput in;
            const auto p = FromPoseWithCovariance(m, &in.covariance);
            in.stamp = p.stamp;
            in.pose = p.pose;
            inbox_.OfferInitialPose(in);
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

void LocalisationComponent::StartSearch(const localisation_core::SessionScan& scan) {
  if (search_.valid()) return;  // one at a time
  SearchAnswer answer;
  answer.generation = search_generation_;
  answer.stamp = scan.geometry.stamp;
  if (pose_hint_check_) {
    if (!session_.OdometryReaches(scan.geometry.stamp)) return;  // the prediction needs it
    const geometry::Pose2D odometry = *session_.OdometryAt(scan.geometry.stamp);
    answer.hint_check = *pose_hint_check_;
    search_ = std::async(std::launch::async, [this, scan, odometry, answer]() mutable {
      answer.hint = answer.hint_check->Check(*global_, scan, odometry);
      return answer;
    });
    return;
  }
  if (!global_ || !session_.OdometryReaches(scan.geometry.stamp)) return;
  // The scans of the last metres count with this one when odometry on both
  // sides of its stamp places it (not the newest sample held beyond it).
  const double t = scan.geometry.stamp;
  const auto odometry =
      session_.OdometryCovers(t) ? session_.OdometryAt(t) : std::optional<geometry::Pose2D>();
  // Hypotheses held are carried by odometry: a scan it does not place yet
  // waits for the next (no search runs now, so asking global_ is safe).
  if (!odometry && global_->HoldingHypotheses()) return;
  search_ = std::async(std::launch::async, [this, scan, odometry, answer]() mutable {
    answer.global = odometry ? global_->Try(scan, *odometry) : global_->Try(scan);
    return answer;
  });
}

void LocalisationComponent::ApplySearch(const SearchAnswer& answer, double now) {
  // The kidnap watch's searches come out of its budget, even one outdated.
  if (answer.tracked && answer.global && kidnap_watch_)
    kidnap_watch_->Spent(answer.global->result.work);
  if (answer.generation != search_generation_) return;  // outdated meanwhile
  if (answer.tracked) {
    ApplyKidnapSearch(answer, now);
    return;
  }
  if (answer.global) ApplyGlobal(*answer.global, answer.stamp, now);
  if (answer.hint && pose_hint_check_) {
    *pose_hint_check_ = *answer.hint_check;  // it counts its attempts
    ApplyHint(*answer.hint, now);
  }
}

void LocalisationComponent::ApplyGlobal(const localisation_core::GlobalStart::Attempt& attempt,
                                        double stamp, double now) {
  std::cout << std::fixed << std::setprecision(3);
  if (attempt.searched) {
    const auto& r = attempt.result;
    std::cout << "localisation: global localisation at t=" << stamp;
    if (r.scans > 1) std::cout << " with " << r.scans - 1 << " scans before it";
    std::cout << ": " << localisation_core::ToString(r.decision);
    if (r.best) {
      std::cout << ", best laser pose (" << r.best->pose.x << ", " << r.best->pose.y << ", "
                << r.best->pose.theta << ") explains " << static_cast<int>(100 * r.best->score)
                << " %";
      if (r.best->newest_score)
        std::cout << " (" << static_cast<int>(100 * *r.best->newest_score) << " % of this scan)";
    }
    if (r.runner_up) {
      std::cout << ", runner-up (" << r.runner_up->pose.x << ", " << r.runner_up->pose.y << ", "
                << r.runner_up->pose.theta << ") " << static_cast<int>(100 * r.runner_up->score)
                << " %";
    }
    if (!r.reason.empty()) std::cout << " (" << r.reason << ")";
    if (!attempt.hypotheses.empty())
      std::cout << "; weighing " << attempt.hypotheses.size() << " hypotheses as the robot moves";
    std::cout << std::endl;
  } else if (!attempt.found && attempt.hypotheses.size() != held_hypotheses_) {
    std::cout << "localisation: " << attempt.hypotheses.size() << " hypotheses left at t=" << stamp
              << std::endl;
  }
  held_hypotheses_ = attempt.found ? 0 : attempt.hypotheses.size();
  if (!attempt.found) {
    start_up_out_ = StartUpMessages{ToPoseArray(attempt.hypotheses, stamp, options_.frames),
                                    ToStartUpStatus(attempt.hypotheses, stamp, options_.frames)};
    return;
  }
  forget_recent_scans_ = true;
  session_.SetInitialPose(*attempt.found, "global localisation", now);
  const auto& p = attempt.found->pose;
  std::cout << "localisation: initial pose set from global localisation: robot at (" << p.x << ", "
            << p.y << ", " << p.theta << ")";
  if (attempt.travel_m)
    std::cout << ", committed to one of " << attempt.seeded << " hypotheses after "
              << *attempt.travel_m << " m of travel";
  std::cout << std::endl;
}

void LocalisationComponent::ApplyHint(const localisation_core::PoseHintCheck::Outcome& outcome,
                                      double now) {
  using Verdict = localisation_core::PoseHintCheck::Verdict;
  const auto& q = outcome.predicted;
  std::cout << std::fixed << std::setprecision(3);
  const std::string& source = pose_hint_check_->Source();
  if (outcome.verdict == Verdict::kFound) {
    const auto& p = outcome.found->pose;
    session_.SetInitialPose(*outcome.found, source + ", confirmed", now);
    std::cout << "localisation: " << source << " confirmed by a local search: robot at (" << p.x
              << ", " << p.y << ", " << p.theta << "), " << std::hypot(p.x - q.x, p.y - q.y)
              << " m and " << std::abs(geometry::WrapAngle(p.theta - q.theta))
              << " rad from where it put the robot" << std::endl;
    pose_hint_check_.reset();
  } else if (outcome.verdict == Verdict::kGiveUp) {
    std::cout << "localisation: WARNING: no local search confirmed " << source
              << " (the last: " << localisation_core::ToString(outcome.result.decision)
              << " within " << pose_hint_check_->RadiusM() << " m and "
              << pose_hint_check_->HeadingRad() << " rad of (" << q.x << ", " << q.y << ", "
              << q.theta << ")); starting from it unconfirmed: publish "
              << dds_common::topics::kInitialPose.name
              << " or request a global relocalisation if the robot was moved" << std::endl;
    session_.NoteProblem(source + " was taken unconfirmed: no local search confirmed it", now);
    session_.ResumeFrom(pose_hint_check_->Hint());
    pose_hint_check_.reset();
  }
}

void LocalisationComponent::TakeBackAsHint() {
  // The session checked the given pose and tied it to the odometry (at its
  // stamp, or the first sample); the correction that makes is the hint.
  const auto latest = session_.Latest();
  if (!latest) return;
  const localisation_core::SessionState hint{session_.Tracker()->MapToOdom(),
                                             latest->covariance.diagonal()};
  session_.ForgetPose();
  pose_hint_check_.emplace(hint, given_pose_source_, hint_check_options_);
  given_pose_source_.clear();
  ++search_generation_;  // a search under way was for what came before
}

void LocalisationComponent::Stop() {
  inbox_.Stop();
  if (worker_.joinable()) worker_.join();
  if (search_.valid()) search_.wait();  // it uses global_
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
      if (search_.valid() &&
          search_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        ApplySearch(search_.get(), now);
      }
      if (relocalise_requested_.exchange(false) && global_) {
        session_.ForgetPose();
        pose_hint_check_.reset();
        given_pose_source_.clear();
        forget_recent_scans_ = true;  // the robot may have been carried away
        ++search_generation_;
        held_hypotheses_ = 0;
        EndKidnapDoubt();
        std::cout << "localisation: relocalising globally, as asked on "
                  << dds_common::topics::kReinitializeGlobalLocalization.name << std::endl;
      }
      if (forget_recent_scans_ && !search_.valid() && global_) {
        global_->ForgetRecentScans();
        forget_recent_scans_ = false;
      }
      std::optional<localisation_core::SessionScan> scan = std::move(inputs.scan);
      inputs.scan.reset();
      if (session_.Apply(inputs, dds_common::topics::kInitialPose.name) > 0) {
        pose_hint_check_.reset();  // a pose published outranks an older hint
        ++search_generation_;
        held_hypotheses_ = 0;
        EndKidnapDoubt();
        if (global_) given_pose_source_ = "the pose on " + dds_common::topics::kInitialPose.name;
        std::cout << "localisation: initial pose "
                  << (session_.HasInitialPose() ? "set" : "held for the first odometry") << " from "
                  << dds_common::topics::kInitialPose.name
                  << (global_ ? "; a search around it confirms it" : "") << std::endl;
      }
      if (!given_pose_source_.empty() && session_.HasInitialPose()) TakeBackAsHint();
      if (scan && session_.WaitingForInitialPose() && (pose_hint_check_ || global_)) {
        StartSearch(*scan);
      }
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
    WatchForKidnapping(*report);
  }
}

void LocalisationComponent::WatchForKidnapping(const localisation_core::ScanReport& report) {
  if (!kidnap_watch_ || pose_hint_check_) return;
  // The points only when the watch uses them (the share, or a search's answer).
  SearchAnswer answer;
  if (kidnap_watch_->CheckDue(report.stamp, report.lost))
    answer.points = localisation_core::LaserPoints(report.scan);
  const bool due =
      kidnap_watch_->Observe(answer.points, report.stamp, report.pose.pose, report.lost);
  if (!kidnap_watch_->InDoubt()) {
    if (kidnap_doubt_) forget_recent_scans_ = true;
    kidnap_doubt_ = false;
    kidnap_hypotheses_ = 0;
    return;
  }
  if (!kidnap_doubt_) {
    std::cout << "localisation: the tracked pose has not explained the scans for "
              << kidnap_watch_->Options().after_s
              << " s: searching the whole map in case the robot was carried away" << std::endl;
    // What the start-up searched and held is of another time.
    if (search_.valid()) return;
    global_->ForgetRecentScans();
  }
  kidnap_doubt_ = true;
  if ((!due && kidnap_hypotheses_ == 0) || search_.valid() ||
      !session_.OdometryCovers(report.stamp))
    return;
  const geometry::Pose2D odometry = *session_.OdometryAt(report.stamp);
  if (due) kidnap_watch_->Searched(report.stamp);
  if (answer.points.empty()) answer.points = localisation_core::LaserPoints(report.scan);
  answer.generation = search_generation_;
  answer.stamp = report.stamp;
  answer.tracked = report.pose.pose;
  search_ = std::async(std::launch::async, [this, scan = report.scan, odometry, answer]() mutable {
    answer.global = global_->Try(scan, odometry);
    return answer;
  });
}

void LocalisationComponent::EndKidnapDoubt() {
  if (kidnap_watch_) kidnap_watch_->Clear();
  kidnap_doubt_ = false;
  kidnap_hypotheses_ = 0;
}

void LocalisationComponent::ApplyKidnapSearch(const SearchAnswer& answer, double now) {
  if (!kidnap_doubt_) return;  // the scans fit again meanwhile: the tracking was right
  const auto& attempt = *answer.global;
  kidnap_hypotheses_ = attempt.found ? 0 : attempt.hypotheses.size();
  if (!attempt.found || session_.WaitingForInitialPose()) return;
  forget_recent_scans_ = true;
  const auto kidnapping =
      kidnap_watch_->Jumped(answer.stamp, answer.points, attempt.found->pose, *answer.tracked);
  if (!kidnapping) return;
  ++kidnappings_;
  // The scans taken while the search ran were tracked from where the robot
  // was lifted: the poses up to the latest of them are of the old track.
  const auto latest = session_.Latest();
  const double old_track_until = latest ? std::max(latest->stamp, answer.stamp) : answer.stamp;
  session_.SetInitialPose(*attempt.found, "the search for a kidnapped robot", now);
  const auto& f = kidnapping->from;
  const auto& t = kidnapping->to;
  std::cout << std::fixed << std::setprecision(3)
            << "localisation: kidnapped: at t=" << answer.stamp << ", after " << kidnapping->doubt_s
            << " s of scans the tracked pose did not explain, the robot was found at (" << t.x
            << ", " << t.y << ", " << t.theta << "), not at (" << f.x << ", " << f.y << ", "
            << f.theta << "); tracking goes on from there after the old track's last pose at t="
            << old_track_until << std::endl;
  session_.NoteProblem("kidnapped: the robot was found " +
                           std::to_string(std::hypot(t.x - f.x, t.y - f.y)) +
                           " m from where it was tracked",
                       now);
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
    kidnappings = kidnappings_;
    if (!session_.WaitingForInitialPose())
      start_up = kidnap_doubt_ ? "tracking, in doubt: searching the map in case the robot was "
                                 "carried away"
                               : "tracking";
    else if (pose_hint_check_)
      start_up = "confirming " + pose_hint_check_->Source();
    else if (held_hypotheses_ > 0)
      start_up = "holding " + std::to_string(held_hypotheses_) + " hypotheses";
    else
      start_up = global_ ? "searching the map" : "waiting for an initial pose";
  }
  if (const uint64_t overflow = inbox_.OdometryOverflow()) {
    report.values.emplace_back("odometry_dropped", std::to_string(overflow));
  }
  for (const auto& peer : node_.PeerProblems()) report.values.emplace_back("peer", peer);
  report.values.emplace_back("start_up", start_up);
  report.values.emplace_back("kidnappings", std::to_string(kidnappings));
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
