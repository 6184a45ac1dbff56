// How a robot gets its pose, and gets it back: one policy that the
// localisation component (live) and replay (offline) both follow, so that a
// log replayed and a robot switched on start alike. DDS-free.
//
// The sources of a pose, in the order they rank:
//  - a pose published on the initial-pose topic, or given at start-up;
//  - a map -> odom correction saved before a restart;
//  - a request to relocalise (forget the pose, search the whole map);
//  - nothing: the scans are searched against the whole map (GlobalStart),
//    an ambiguous answer (a symmetric building) starts hypotheses that the
//    robot's motion tells apart, and one is committed.
// A saved correction, and a given pose when confirm_given_poses is set (live:
// it holds for the first odometry sample, which may come after the robot
// moved), are hints: a local search around the pose they predict confirms
// them (PoseHintCheck) before the tracking trusts them. A log's initial pose
// is that of its first laser line, a fact: replay takes it as it is.
// Once tracking, the kidnap watch (KidnapWatch) looks for a robot carried
// elsewhere, and its searches move the tracking when they find one; on a map
// with twins (FindMapTwins) the twin watch (TwinWatch) looks for a robot
// tracked at the twin of where it is, which the share of a scan the tracked
// pose explains cannot tell, and a search of the whole map confirms the twin
// (or finds the robot elsewhere) before the tracking moves.
//
// The policy never runs a search itself where the caller cannot afford it:
// SearchAt and Watch hand out a search to run (Run: on a thread of its own in
// the component, inline in replay; one at a time), and Apply takes its answer
// back, ignoring one made outdated meanwhile (a pose given, a relocalisation
// asked for). Everything else is called from one thread.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "structloc/localisation_core/global/global_start.hpp"
#include "structloc/localisation_core/global/kidnap_watch.hpp"
#include "structloc/localisation_core/global/map_twins.hpp"
#include "structloc/localisation_core/global/pose_hint_check.hpp"
#include "structloc/localisation_core/global/twin_watch.hpp"
#include "structloc/localisation_core/tracking/tracking_session.hpp"

namespace structloc::localisation_core {

struct StartUpOptions {
  GlobalLocaliserOptions global;  // the whole-map search
  RecentScansOptions recent;      // the scans of the last metres searched with each
  HypothesisOptions hypotheses;   // an ambiguous answer's hypotheses
  KidnapOptions kidnap;           // a tracked robot carried elsewhere
  MapTwinOptions twins;           // the map's twins, that a tracked robot may be at
  // Confirming a hint; its radius_m is raised to the tracker's
  // reacquire_max_radius_m (a hint is searched at least as wide as a lost
  // tracker searches).
  PoseHintCheckOptions hint;
  // Whether a given pose is a hint to confirm (live) or a fact (a log's
  // initial pose, that of its first laser line).
  bool confirm_given_poses = true;
};

// A search the policy asks for. Run fills in its answer; Apply takes it back.
struct StartUpSearch {
  enum class Kind {
    kGlobal,   // a robot without a pose, against the whole map (or the hypotheses weighed)
    kHint,     // a hint confirmed by a local search around it
    kKidnap,   // the kidnap watch's search for a tracked robot
    kTwin,     // the twin watch's decision, checked by a whole-map search
    kRecheck,  // a pose a kidnap search found, refused on its scan, weighed on a later one
  };
  Kind kind = Kind::kGlobal;
  uint64_t generation = 0;  // the policy's when it was asked for
  SessionScan scan;
  std::optional<geometry::Pose2D> odometry;  // the robot's odometric pose at the scan
  std::optional<PoseHintCheck> hint_check;   // kHint: a copy, counting its attempts
  geometry::Pose2D tracked;  // kKidnap, kTwin, kRecheck: the robot pose tracked at the scan
  std::vector<Eigen::Vector2d> points;  // kKidnap, kTwin, kRecheck: the scan's laser-frame points
  std::optional<TwinDecision> twin;     // kTwin: the decision (Run refines its twin)
  std::optional<GlobalResult> twin_check;   // kTwin: the search of the whole map for the scan
  std::optional<InitialPoseInput> recheck;  // kRecheck: the pose carried to this scan
  // The answer (laser poses in the results, robot poses in what was found).
  std::optional<GlobalStart::Attempt> global;  // kGlobal, kKidnap
  std::optional<PoseHintCheck::Outcome> hint;  // kHint
  double seconds = 0.0;                        // wall time Run took

  double Stamp() const { return scan.geometry.stamp; }
};

// What taking a search's answer back did.
struct StartUpOutcome {
  bool outdated = false;  // asked for before a pose was given or a relocalisation
  bool pose_set = false;  // the session has a new pose from it
  // kGlobal: the hypotheses held after it, for the caller to publish.
  std::vector<Hypothesis> hypotheses;
  std::optional<Kidnapping> kidnapping;
  std::vector<std::string> log;  // sentences for the caller's log, in order
};

class StartUpPolicy {
 public:
  // `world` null: nothing is searched (a given pose is taken as it is). The
  // world must outlive the policy. A world the search cannot hold (too large
  // for its grid) leaves the policy without searches, and says why
  // (NoSearchReason).
  StartUpPolicy(const world_model::WorldModel* world, const geometry::Pose2D& sensor_mount,
                const SessionOptions& session, const StartUpOptions& options);

  bool CanSearch() const { return global_ != nullptr; }
  const std::string& NoSearchReason() const { return no_search_reason_; }
  const StartUpOptions& Options() const { return options_; }

  // The sources of a pose. Each returns the sentence for the caller's log.
  // A pose given at start-up (`source`: "the initial pose from the command line").
  std::string GivenAtStart(TrackingSession& session, const geometry::Pose2D& pose,
                           TrackingSession::InitialPoseWhen when, const std::string& source);
  // A saved correction (`source`: "the pose saved in F").
  std::string Resume(TrackingSession& session, const SessionState& saved,
                     const std::string& source);
  // After the session accepted a pose from the initial-pose `topic`.
  std::string GivenOnTopic(const TrackingSession& session, const std::string& topic);
  // A request to relocalise globally on `topic` (nullopt: nothing to search with).
  std::optional<std::string> Relocalise(TrackingSession& session, const std::string& topic);
  // What the robot waits for at start-up (nullopt: it has a pose or a hint).
  std::optional<std::string> WaitingSentence(const TrackingSession& session,
                                             const std::string& initial_pose_topic) const;

  // Before each scan goes to the session: a given pose that has just started
  // the tracking is taken back as a hint to confirm.
  void Tend(TrackingSession& session);
  // Without a pose, at a scan: the search to run for it, if one is due now.
  std::optional<StartUpSearch> SearchAt(const TrackingSession& session, const SessionScan& scan);
  // After a tracked scan: the kidnap watch, and its search when one is due
  // (sentences for the log go to `log`).
  std::optional<StartUpSearch> Watch(const TrackingSession& session, const ScanReport& report,
                                     std::vector<std::string>& log);
  // Runs a search handed out (any thread; one at a time).
  void Run(StartUpSearch& search);
  // Takes a search's answer back; every search handed out must come back
  // here, outdated or not.
  StartUpOutcome Apply(TrackingSession& session, const StartUpSearch& search, double now);

  bool SearchUnderway() const { return search_out_; }
  // For diagnostics: what the start-up is doing.
  std::string State(const TrackingSession& session) const;
  size_t HeldHypotheses() const { return held_hypotheses_; }
  size_t Kidnappings() const { return kidnappings_; }
  bool InDoubt() const { return doubt_; }

 private:
  void ApplyGlobal(TrackingSession& session, const StartUpSearch& search, double now,
                   StartUpOutcome& out);
  void ApplyHint(TrackingSession& session, const PoseHintCheck::Outcome& outcome, double now,
                 StartUpOutcome& out);
  void ApplyKidnap(TrackingSession& session, const StartUpSearch& search, double now,
                   StartUpOutcome& out);
  void ApplyTwin(TrackingSession& session, const StartUpSearch& search, double now,
                 StartUpOutcome& out);
  void ApplyRecheck(TrackingSession& session, const StartUpSearch& search, double now,
                    StartUpOutcome& out);
  // A kidnapping found (by a search or the twin watch) moves the tracking.
  // `source`: what found it, for the session; `how`: the log sentence's middle.
  void Jump(TrackingSession& session, const Kidnapping& kidnapping, const InitialPoseInput& found,
            const std::string& source, const std::string& how, double now, StartUpOutcome& out);
  // The scans searched before, and the hypotheses held, are of another
  // time: forgotten now, or when the search under way comes back.
  void ForgetRecentScans();
  void EndDoubt();
  StartUpSearch Hand(StartUpSearch::Kind kind, const SessionScan& scan);
  // The robot pose near `robot` whose laser pose explains the scan
  // (laser-frame points) best: GlobalLocaliser::Polish.
  geometry::Pose2D Polished(const std::vector<Eigen::Vector2d>& laser_points,
                            const geometry::Pose2D& robot) const;

  StartUpOptions options_;
  std::unique_ptr<GlobalStart> global_;
  std::unique_ptr<KidnapWatch> watch_;
  std::unique_ptr<TwinWatch> twins_;  // null: the map has no twins
  geometry::Pose2D mount_;
  Eigen::Matrix3d initial_covariance_;  // of a pose found (the tracker's initial covariance)
  std::string no_search_reason_;
  // A hint until it is confirmed or given up on.
  std::optional<PoseHintCheck> hint_;
  // A given pose's source, until the session started tracking from it and it
  // is taken back as a hint (empty: none waiting).
  std::string given_source_;
  uint64_t generation_ = 0;  // outdates the searches asked for before
  bool search_out_ = false;
  bool forget_when_back_ = false;
  size_t held_hypotheses_ = 0;  // after the last global attempt applied
  bool doubt_ = false;          // the kidnap watch is in doubt
  // A pose a kidnap search found that explained its scan clearly better than
  // the tracked one but less than the normal share (a scan taken while the
  // robot turned fits less everywhere): carried by odometry and weighed again
  // on the scans until `until`.
  struct Refused {
    InitialPoseInput found;
    geometry::Pose2D odometry;  // the robot's odometric pose at found.stamp
    double until = 0.0;
    std::optional<double> last_weighed;  // weighed again once per kidnap check_period_s
  };
  std::optional<Refused> refused_;
  size_t kidnappings_ = 0;
};

}  // namespace structloc::localisation_core
