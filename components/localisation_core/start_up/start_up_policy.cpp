// The start-up and recovery policy (see header).
#include "structloc/localisation_core/start_up/start_up_policy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace structloc::localisation_core {
namespace {

std::ostringstream Sentence() {
  std::ostringstream s;
  s << std::fixed << std::setprecision(3);
  return s;
}

void Write(std::ostringstream& s, const geometry::Pose2D& p) {
  s << "(" << p.x << ", " << p.y << ", " << p.theta << ")";
}

// A global attempt as one sentence: the search's decision and its best
// poses, or how many hypotheses are left.
std::string DescribeSearch(const GlobalStart::Attempt& attempt, double stamp) {
  auto s = Sentence();
  const auto& r = attempt.result;
  s << "global localisation at t=" << stamp;
  if (r.scans > 1) s << " with " << r.scans - 1 << " scans before it";
  s << ": " << ToString(r.decision);
  if (r.best) {
    s << ", best laser pose ";
    Write(s, r.best->pose);
    s << " explains " << static_cast<int>(100 * r.best->score) << " %";
    if (r.best->newest_score)
      s << " (" << static_cast<int>(100 * *r.best->newest_score) << " % of this scan)";
  }
  if (r.runner_up) {
    s << ", runner-up ";
    Write(s, r.runner_up->pose);
    s << " " << static_cast<int>(100 * r.runner_up->score) << " %";
  }
  if (!r.reason.empty()) s << " (" << r.reason << ")";
  if (!attempt.hypotheses.empty())
    s << "; weighing " << attempt.hypotheses.size() << " hypotheses as the robot moves";
  return s.str();
}

// The robot's odometric pose at `t`: the one given with the scan, else the
// session's when odometry on both sides of `t` places it (not the newest
// sample held beyond it).
std::optional<geometry::Pose2D> OdometryAt(const TrackingSession& session,
                                           const std::optional<geometry::Pose2D>& given, double t) {
  if (given) return given;
  if (session.OdometryCovers(t)) return session.OdometryAt(t);
  return std::nullopt;
}

}  // namespace

StartUpPolicy::StartUpPolicy(const world_model::WorldModel* world,
                             const geometry::Pose2D& sensor_mount, const SessionOptions& session,
                             const StartUpOptions& options)
    : options_(options),
      mount_(sensor_mount),
      initial_covariance_(session.tracker.InitialCovariance()) {
  CheckHypothesisOptions(options.hypotheses);
  CheckKidnapOptions(options.kidnap);
  CheckMapTwinOptions(options.twins);
  options_.hint.radius_m = std::max(options_.hint.radius_m, session.tracker.reacquire_max_radius_m);
  options_.hint.max_radius_m = std::max(options_.hint.max_radius_m, options_.hint.radius_m);
  if (world == nullptr) return;
  try {
    global_ =
        std::make_unique<GlobalStart>(*world, sensor_mount, session.tracker.InitialCovariance(),
                                      options.global, options.recent, options.hypotheses);
  } catch (const std::invalid_argument& e) {  // a map too large for the search's grid
    no_search_reason_ = e.what();
    return;
  }
  watch_ = std::make_unique<KidnapWatch>(global_->Localiser(), sensor_mount, options.kidnap);
  auto twins = FindMapTwins(*world, global_->Localiser(), options.twins);
  if (!twins.empty())
    twins_ = std::make_unique<TwinWatch>(global_->Localiser(), sensor_mount, std::move(twins),
                                         options.hypotheses, options.twins.allowance_points);
}

std::string StartUpPolicy::GivenAtStart(TrackingSession& session, const geometry::Pose2D& pose,
                                        TrackingSession::InitialPoseWhen when,
                                        const std::string& source) {
  session.ExpectInitialPose(pose, when);
  const bool confirm = global_ && options_.confirm_given_poses;
  if (confirm) given_source_ = source;
  const bool at_odometry = when == TrackingSession::InitialPoseWhen::kAtFirstOdometry;
  return source + (at_odometry ? ", for the first odometry" : ", at the first scan") +
         (confirm ? "; a search around it confirms it" : "");
}

std::string StartUpPolicy::Resume(TrackingSession& session, const SessionState& saved,
                                  const std::string& source) {
  if (global_) {
    hint_.emplace(saved, source, options_.hint);
    return "resuming from " + source + " once a search around it confirms it";
  }
  session.ResumeFrom(saved);
  return "resuming from " + source;
}

std::string StartUpPolicy::GivenOnTopic(const TrackingSession& session, const std::string& topic) {
  hint_.reset();  // a pose published outranks an older hint
  ++generation_;
  held_hypotheses_ = 0;
  EndDoubt();
  const bool confirm = global_ && options_.confirm_given_poses;
  if (confirm) given_source_ = "the pose on " + topic;
  return std::string("initial pose ") +
         (session.HasInitialPose() ? "set" : "held for the first odometry") + " from " + topic +
         (confirm ? "; a search around it confirms it" : "");
}

std::optional<std::string> StartUpPolicy::Relocalise(TrackingSession& session,
                                                     const std::string& topic) {
  if (!global_) return std::nullopt;
  session.ForgetPose();
  hint_.reset();
  given_source_.clear();
  ForgetRecentScans();  // the robot may have been carried away
  ++generation_;
  held_hypotheses_ = 0;
  EndDoubt();
  return "relocalising globally, as asked on " + topic;
}

std::optional<std::string> StartUpPolicy::WaitingSentence(
    const TrackingSession& session, const std::string& initial_pose_topic) const {
  if (!session.WaitingForInitialPose() || hint_) return std::nullopt;
  if (!global_)
    return "no initial pose: waiting for one on " + initial_pose_topic +
           (no_search_reason_.empty() ? ""
                                      : " (the map cannot be searched: " + no_search_reason_ + ")");
  return "no initial pose: locating the robot globally from the scans until one pose explains "
         "a scan without a doubt (or one comes on " +
         initial_pose_topic + ")";
}

void StartUpPolicy::Tend(TrackingSession& session) {
  if (given_source_.empty() || !session.HasInitialPose()) return;
  // The session checked the given pose and tied it to the odometry (at its
  // stamp, or the first sample); the correction that makes is the hint.
  const auto latest = session.Latest();
  if (!latest) return;
  const SessionState hint{session.Tracker()->MapToOdom(), latest->covariance.diagonal()};
  session.ForgetPose();
  hint_.emplace(hint, given_source_, options_.hint);
  given_source_.clear();
  ++generation_;  // a search under way was for what came before
}

StartUpSearch StartUpPolicy::Hand(StartUpSearch::Kind kind, const SessionScan& scan) {
  StartUpSearch search;
  search.kind = kind;
  search.generation = generation_;
  search.scan = scan;
  search_out_ = true;
  return search;
}

std::optional<StartUpSearch> StartUpPolicy::SearchAt(const TrackingSession& session,
                                                     const SessionScan& scan) {
  if (search_out_ || !global_ || !session.WaitingForInitialPose()) return std::nullopt;
  const double t = scan.geometry.stamp;
  // A scan older than the first odometry cannot be tied to it.
  if (!scan.odometry && !session.OdometryReaches(t)) return std::nullopt;
  if (hint_) {
    auto search = Hand(StartUpSearch::Kind::kHint, scan);
    search.odometry = scan.odometry ? scan.odometry : session.OdometryAt(t);
    search.hint_check = *hint_;
    return search;
  }
  // The scans of the last metres count with this one when odometry places it.
  const auto odometry = OdometryAt(session, scan.odometry, t);
  // Hypotheses held are carried by odometry: a scan it does not place yet
  // waits for the next.
  if (!odometry && global_->HoldingHypotheses()) return std::nullopt;
  auto search = Hand(StartUpSearch::Kind::kGlobal, scan);
  search.odometry = odometry;
  return search;
}

std::optional<StartUpSearch> StartUpPolicy::Watch(const TrackingSession& session,
                                                  const ScanReport& report,
                                                  std::vector<std::string>& log) {
  if (!watch_ || hint_ || report.kind != ScanReport::Kind::kTracked) return std::nullopt;
  // The points only when the watch uses them (the share, or a search's answer).
  std::vector<Eigen::Vector2d> points;
  const bool twin_due = twins_ && !doubt_ && !report.lost && twins_->Due(report.pose.pose);
  if (twin_due || watch_->CheckDue(report.stamp, report.lost)) points = LaserPoints(report.scan);
  const bool due = watch_->Observe(points, report.stamp, report.pose.pose, report.lost);
  if (!watch_->InDoubt()) {
    if (doubt_) ForgetRecentScans();
    doubt_ = false;
    refused_.reset();
    if (!twin_due) return std::nullopt;
    // The twin must explain the scan as well as the tracked pose did while
    // all was well, as a kidnapping's new pose must (KidnapWatch::Jumped).
    // Weighed whether or not its search can run now: the evidence stays at
    // the bound, and decides again at the next step.
    const auto normal = watch_->NormalShare();
    const double min_share = normal ? *normal - options_.kidnap.max_share_below_normal : 0.0;
    auto twin = twins_->Observe(points, report.stamp, report.pose.pose, min_share);
    if (!twin || search_out_ || !watch_->CanAfford()) return std::nullopt;
    auto search = Hand(StartUpSearch::Kind::kTwin, report.scan);
    search.tracked = report.pose.pose;
    search.twin = twin;
    search.points = std::move(points);
    return search;
  }
  if (!doubt_) {
    auto s = Sentence();
    s << "the tracked pose has not explained the scans for " << watch_->Options().after_s
      << " s: searching the whole map in case the robot was carried away";
    log.push_back(s.str());
    ForgetRecentScans();          // what the start-up searched and held is of another time
    if (twins_) twins_->Clear();  // the kidnap watch's searches decide now
    doubt_ = true;
  }
  if (search_out_) return std::nullopt;
  const auto odometry = OdometryAt(session, report.odometry, report.stamp);
  if (refused_ && report.stamp > refused_->until) refused_.reset();
  const bool recheck_due = refused_ && odometry &&
                           (!refused_->last_weighed || report.stamp - *refused_->last_weighed >=
                                                           options_.kidnap.check_period_s);
  if (recheck_due) {  // while the tracker is lost too
    refused_->last_weighed = report.stamp;
    if (points.empty()) points = LaserPoints(report.scan);
    auto search = Hand(StartUpSearch::Kind::kRecheck, report.scan);
    const geometry::Pose2D moved = geometry::Between(refused_->odometry, *odometry);
    search.recheck = InitialPoseInput{report.stamp, geometry::Compose(refused_->found.pose, moved),
                                      refused_->found.covariance};
    search.tracked = report.pose.pose;
    search.points = std::move(points);
    return search;
  }
  if (!due && !global_->HoldingHypotheses()) return std::nullopt;
  if (!odometry) return std::nullopt;
  if (due) watch_->Searched(report.stamp);
  auto search = Hand(StartUpSearch::Kind::kKidnap, report.scan);
  search.odometry = odometry;
  search.tracked = report.pose.pose;
  search.points = points.empty() ? LaserPoints(report.scan) : std::move(points);
  return search;
}

geometry::Pose2D StartUpPolicy::Polished(const std::vector<Eigen::Vector2d>& laser_points,
                                         const geometry::Pose2D& robot) const {
  const auto& localiser = global_->Localiser();
  const auto points = localiser.FitPoints(laser_points, options_.global.rank_points);
  const auto laser = localiser.Polish(points, geometry::Compose(robot, mount_));
  return geometry::Compose(laser, geometry::Inverse(mount_));
}

void StartUpPolicy::Run(StartUpSearch& search) {
  const auto t0 = std::chrono::steady_clock::now();
  switch (search.kind) {
    case StartUpSearch::Kind::kHint:
      search.hint = search.hint_check->Check(*global_, search.scan, *search.odometry);
      break;
    case StartUpSearch::Kind::kGlobal:
    case StartUpSearch::Kind::kKidnap:
      search.global =
          search.odometry ? global_->Try(search.scan, *search.odometry) : global_->Try(search.scan);
      break;
    case StartUpSearch::Kind::kTwin:
      search.twin->twin = Polished(search.points, search.twin->twin);
      search.twin_check = global_->Localiser().Locate(search.points);
      break;
    case StartUpSearch::Kind::kRecheck:
      search.recheck->pose = Polished(search.points, search.recheck->pose);
      break;
  }
  search.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

StartUpOutcome StartUpPolicy::Apply(TrackingSession& session, const StartUpSearch& search,
                                    double now) {
  search_out_ = false;
  if (forget_when_back_) ForgetRecentScans();
  StartUpOutcome out;
  // The kidnap and twin watches' searches come out of the kidnap watch's
  // budget, even one outdated.
  if (search.kind == StartUpSearch::Kind::kKidnap && search.global)
    watch_->Spent(search.global->result.work);
  if (search.kind == StartUpSearch::Kind::kTwin && search.twin_check)
    watch_->Spent(search.twin_check->work);
  if (search.generation != generation_) {
    out.outdated = true;
    return out;
  }
  switch (search.kind) {
    case StartUpSearch::Kind::kGlobal:
      if (search.global) ApplyGlobal(session, search, now, out);
      break;
    case StartUpSearch::Kind::kHint:
      if (search.hint && hint_) {
        *hint_ = *search.hint_check;  // it counts its attempts
        ApplyHint(session, *search.hint, now, out);
      }
      break;
    case StartUpSearch::Kind::kKidnap:
      if (search.global) ApplyKidnap(session, search, now, out);
      break;
    case StartUpSearch::Kind::kTwin:
      if (search.twin && search.twin_check) ApplyTwin(session, search, now, out);
      break;
    case StartUpSearch::Kind::kRecheck:
      if (search.recheck) ApplyRecheck(session, search, now, out);
      break;
  }
  if (out.pose_set) {  // what was weighed was of the pose before
    if (twins_) twins_->Clear();
    refused_.reset();
  }
  return out;
}

void StartUpPolicy::ApplyGlobal(TrackingSession& session, const StartUpSearch& search, double now,
                                StartUpOutcome& out) {
  const auto& attempt = *search.global;
  const double stamp = search.Stamp();
  if (attempt.searched) {
    out.log.push_back(DescribeSearch(attempt, stamp));
  } else if (!attempt.found && attempt.hypotheses.size() != held_hypotheses_) {
    auto s = Sentence();
    s << attempt.hypotheses.size() << " hypotheses left at t=" << stamp;
    out.log.push_back(s.str());
  }
  held_hypotheses_ = attempt.found ? 0 : attempt.hypotheses.size();
  if (!attempt.found) {
    out.hypotheses = attempt.hypotheses;
    return;
  }
  ForgetRecentScans();
  out.pose_set = session.SetInitialPose(*attempt.found, "global localisation", now) !=
                 TrackingSession::InitialPoseOutcome::kRejected;
  auto s = Sentence();
  s << "initial pose set from global localisation: robot at ";
  Write(s, attempt.found->pose);
  if (attempt.travel_m)
    s << ", committed to one of " << attempt.seeded << " hypotheses after " << *attempt.travel_m
      << " m of travel";
  out.log.push_back(s.str());
}

void StartUpPolicy::ApplyHint(TrackingSession& session, const PoseHintCheck::Outcome& outcome,
                              double now, StartUpOutcome& out) {
  using Verdict = PoseHintCheck::Verdict;
  const auto& q = outcome.predicted;
  const std::string& source = hint_->Source();
  auto s = Sentence();
  if (outcome.verdict == Verdict::kFound) {
    const auto& p = outcome.found->pose;
    out.pose_set = session.SetInitialPose(*outcome.found, source + ", confirmed", now) !=
                   TrackingSession::InitialPoseOutcome::kRejected;
    s << source << " confirmed by a local search: robot at ";
    Write(s, p);
    s << ", " << std::hypot(p.x - q.x, p.y - q.y) << " m and "
      << std::abs(geometry::WrapAngle(p.theta - q.theta)) << " rad from where it put the robot";
    out.log.push_back(s.str());
    hint_.reset();
  } else if (outcome.verdict == Verdict::kGiveUp) {
    s << "WARNING: no local search confirmed " << source
      << " (the last: " << ToString(outcome.result.decision) << " within " << hint_->RadiusM()
      << " m and " << hint_->HeadingRad() << " rad of ";
    Write(s, q);
    s << ")); starting from it unconfirmed: publish an initial pose or request a global "
         "relocalisation if the robot was moved";
    out.log.push_back(s.str());
    session.NoteProblem(source + " was taken unconfirmed: no local search confirmed it", now);
    session.ResumeFrom(hint_->Hint());
    out.pose_set = true;
    hint_.reset();
  }
}

void StartUpPolicy::ApplyKidnap(TrackingSession& session, const StartUpSearch& search, double now,
                                StartUpOutcome& out) {
  if (!doubt_) return;  // the scans fit again meanwhile: the tracking was right
  const auto& attempt = *search.global;
  if (!attempt.found || session.WaitingForInitialPose()) return;
  ForgetRecentScans();
  KidnapWatch::Comparison c;
  const auto kidnapping =
      watch_->Jumped(search.Stamp(), search.points, attempt.found->pose, search.tracked, &c);
  if (!kidnapping) {
    if (c.far && c.better && !c.as_well_as_normal && search.odometry)
      refused_ =
          Refused{*attempt.found, *search.odometry, search.Stamp() + options_.kidnap.after_s, {}};
    return;
  }
  auto s = Sentence();
  s << "after " << kidnapping->doubt_s << " s of scans the tracked pose did not explain";
  Jump(session, *kidnapping, *attempt.found, "the search for a kidnapped robot", s.str(), now, out);
}

void StartUpPolicy::ApplyTwin(TrackingSession& session, const StartUpSearch& search, double now,
                              StartUpOutcome& out) {
  twins_->Clear();  // whatever the search says, the evidence starts again
  if (doubt_ || session.WaitingForInitialPose()) return;
  const auto& twin = *search.twin;
  const auto& check = *search.twin_check;
  if (!check.best) return;
  // The twin is where the robot is only if no place explains the scan
  // better: a search of one scan ranks the twin first when the detail that
  // tells it from the tracked pose is in view (the evidence rose there), and
  // another place ranked first (a corridor the same seen both ways) is not
  // the twin's to claim.
  const geometry::Pose2D twin_laser = geometry::Compose(twin.twin, mount_);
  const bool twin_first = !Distinct(check.best->pose, twin_laser, options_.global);
  auto s = Sentence();
  if (twin_first) {
    const Kidnapping kidnapping{twin.stamp, twin.tracked, twin.twin, twin.stamp - twin.since};
    watch_->Clear();
    s << "the scans since t=" << twin.since
      << " fit the twin of the tracked place (the map is the same there but for a detail) "
         "better";
    Jump(session, kidnapping, {twin.stamp, twin.twin, initial_covariance_},
         "the twin watch and a search of the map", s.str(), now, out);
    return;
  }
  // Neither: if the search found a place that explains the scan clearly
  // better, the robot may have been carried elsewhere (to a place like the
  // one it was in, so that the share sank too slowly to raise a doubt): the
  // kidnap watch's searches (with hypotheses, for a place that has a twin
  // too) take over.
  const geometry::Pose2D found = geometry::Compose(check.best->pose, geometry::Inverse(mount_));
  if (watch_->ClearlyBetter(search.points, found, twin.tracked)) watch_->Doubt(twin.stamp);
}

void StartUpPolicy::ApplyRecheck(TrackingSession& session, const StartUpSearch& search, double now,
                                 StartUpOutcome& out) {
  if (!doubt_ || !refused_ || session.WaitingForInitialPose()) return;
  const auto& found = *search.recheck;
  const auto kidnapping = watch_->Jumped(search.Stamp(), search.points, found.pose, search.tracked);
  if (!kidnapping) return;
  auto s = Sentence();
  s << "after " << kidnapping->doubt_s
    << " s of scans the tracked pose did not explain, by a search's pose of t="
    << refused_->found.stamp << " weighed again on a later scan";
  refused_.reset();
  Jump(session, *kidnapping, found, "the search for a kidnapped robot", s.str(), now, out);
}

void StartUpPolicy::Jump(TrackingSession& session, const Kidnapping& kidnapping,
                         const InitialPoseInput& found, const std::string& source,
                         const std::string& how, double now, StartUpOutcome& out) {
  // The scans taken while the search ran were tracked from where the robot
  // was lifted: the poses up to the latest of them are of the old track.
  const auto latest = session.Latest();
  const double old_track_until =
      latest ? std::max(latest->stamp, kidnapping.stamp) : kidnapping.stamp;
  out.pose_set =
      session.SetInitialPose(found, source, now) != TrackingSession::InitialPoseOutcome::kRejected;
  auto s = Sentence();
  if (!out.pose_set) {  // the session says why (NoteProblem); the tracking goes on as it was
    s << "a kidnapped robot was found at t=" << kidnapping.stamp << " (" << how
      << "), but the session refused the pose";
    out.log.push_back(s.str());
    return;
  }
  ++kidnappings_;
  out.kidnapping = kidnapping;
  s << "kidnapped: at t=" << kidnapping.stamp << ", " << how << ", the robot was found at ";
  Write(s, kidnapping.to);
  s << ", not at ";
  Write(s, kidnapping.from);
  s << "; tracking goes on from there after the old track's last pose at t=" << old_track_until;
  out.log.push_back(s.str());
  session.NoteProblem("kidnapped: the robot was found " +
                          std::to_string(std::hypot(kidnapping.to.x - kidnapping.from.x,
                                                    kidnapping.to.y - kidnapping.from.y)) +
                          " m from where it was tracked",
                      now);
}

void StartUpPolicy::ForgetRecentScans() {
  if (!global_) return;
  if (search_out_) {
    forget_when_back_ = true;  // the search under way uses them
    return;
  }
  global_->ForgetRecentScans();
  forget_when_back_ = false;
}

void StartUpPolicy::EndDoubt() {
  if (watch_) watch_->Clear();
  refused_.reset();
  if (twins_) twins_->Clear();
  doubt_ = false;
}

std::string StartUpPolicy::State(const TrackingSession& session) const {
  if (!session.WaitingForInitialPose()) {
    return doubt_ ? "tracking, in doubt: searching the map in case the robot was carried away"
                  : "tracking";
  }
  if (hint_) return "confirming " + hint_->Source();
  if (held_hypotheses_ > 0) return "holding " + std::to_string(held_hypotheses_) + " hypotheses";
  return global_ ? "searching the map" : "waiting for an initial pose";
}

}  // namespace structloc::localisation_core
