// A saved map -> odom correction is a hint after a restart, not a fact: the
// odometry drifted while the localisation was down (and the file may be old),
// and a tracker resumed from a stale correction gates out the scans that
// would mend it and coasts on, metres off, while it seems sure of itself.
// SavedPoseCheck confirms the correction with a local search around the pose
// it predicts at each scan (GlobalStart::TryNear) and hands back the pose
// found; where two poses explain the scan equally well (along a corridor) the
// prediction breaks the tie, as a tracker's prior would (NearestOfTie). After
// `attempts` scans with nothing found without a doubt it gives up, and the
// caller resumes from the correction unconfirmed, as a robot in a featureless
// place must. DDS-free.
#pragma once

#include <optional>

#include "structloc/localisation_core/global_start.hpp"
#include "structloc/localisation_core/tracking_session.hpp"

namespace structloc::localisation_core {

struct SavedPoseCheckOptions {
  double radius_m = 2.0;         // laser positions searched around the predicted one
  double heading_rad = 0.52;     // headings searched either side of the predicted one (30 deg)
  double tie_distance_m = 0.3;   // of two equally good poses, one this near the prediction ...
  double tie_heading_rad = 0.1;  // ... and turned at most this much from it is taken
  int attempts = 10;             // scans tried before resuming unconfirmed
};

class SavedPoseCheck {
 public:
  SavedPoseCheck(const SessionState& saved, const SavedPoseCheckOptions& options);

  enum class Verdict { kFound, kTryAgain, kGiveUp };
  struct Outcome {
    Verdict verdict = Verdict::kTryAgain;
    geometry::Pose2D predicted;             // the robot pose the saved correction gives
    std::optional<InitialPoseInput> found;  // when kFound
    GlobalResult result;                    // the search's answer (laser poses)
  };
  // One scan and the odometry pose at its stamp.
  Outcome Check(const GlobalStart& search, const SessionScan& scan,
                const geometry::Pose2D& odometry_at_scan);

  const SessionState& Saved() const { return saved_; }

 private:
  SessionState saved_;
  SavedPoseCheckOptions options_;
  int tried_ = 0;
};

}  // namespace structloc::localisation_core
