// A pose the localisation is handed is a hint, not a fact. A map -> odom
// correction saved before a restart has gone stale while the odometry ran on
// (and the file may be old); an initial pose given at start-up holds for the
// first odometry sample, which may reach the localisation only after the
// robot has moved (DDS readers match one by one, later on a lossy network),
// and an operator's pose is approximate. A tracker started from such a hint
// gates out the scans that would mend it and coasts on, a metre off, while
// it seems sure of itself. PoseHintCheck confirms the hint's correction with
// a local search around the pose it predicts at each scan
// (GlobalStart::TryNear) and hands back the pose found; where two poses
// explain the scan equally well (along a corridor) the prediction breaks the
// tie, as a tracker's prior would (NearestOfTie). The window searched spans
// the hint's own uncertainty: an operator's click (RViz gives 0.5 m and 15 deg
// of standard deviation by default) is searched 3 sigma wide where that
// exceeds the default window, so a pose given 40 deg off is mended rather than
// taken unconfirmed. After `attempts` scans with nothing found without a doubt
// it gives up, and the caller starts from the hint unconfirmed, as a robot in a
// featureless place must. DDS-free.
#pragma once

#include <optional>
#include <string>

#include "structloc/localisation_core/global/global_start.hpp"
#include "structloc/localisation_core/tracking/tracking_session.hpp"

namespace structloc::localisation_core {

struct PoseHintCheckOptions {
  double radius_m = 2.0;         // laser positions searched around the predicted one, at least
  double heading_rad = 0.52;     // headings searched either side of it, at least (30 deg)
  double sigmas = 3.0;           // the window spans this many of the hint's standard deviations ...
  double max_radius_m = 5.0;     // ... but no farther (the search's cost grows with the area)
  double tie_distance_m = 0.3;   // of two equally good poses, one this near the prediction ...
  double tie_heading_rad = 0.1;  // ... and turned at most this much from it is taken
  int attempts = 10;             // scans tried before resuming unconfirmed
};

class PoseHintCheck {
 public:
  // `source` names the hint in messages ("the pose saved in F").
  PoseHintCheck(const SessionState& hint, std::string source, const PoseHintCheckOptions& options);

  enum class Verdict { kFound, kTryAgain, kGiveUp };
  struct Outcome {
    Verdict verdict = Verdict::kTryAgain;
    geometry::Pose2D predicted;             // the robot pose the hint's correction gives
    std::optional<InitialPoseInput> found;  // when kFound
    GlobalResult result;                    // the search's answer (laser poses)
  };
  // One scan and the odometry pose at its stamp.
  Outcome Check(const GlobalStart& search, const SessionScan& scan,
                const geometry::Pose2D& odometry_at_scan);

  const SessionState& Hint() const { return hint_; }
  const std::string& Source() const { return source_; }
  // The window searched around the predicted pose: the options' widened to the hint's spread.
  double RadiusM() const { return radius_m_; }
  double HeadingRad() const { return heading_rad_; }

 private:
  SessionState hint_;
  std::string source_;
  PoseHintCheckOptions options_;
  double radius_m_ = 0.0;
  double heading_rad_ = 0.0;
  int tried_ = 0;
};

}  // namespace structloc::localisation_core
