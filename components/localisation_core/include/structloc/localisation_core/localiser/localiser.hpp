// One position update (thesis 3.4-3.6 and 6.5): scan + odometric pose in, corrected
// pose with covariance, matches, quality and a lost verdict out. Owns every
// buffer it needs, sized at construction, so that the steady-state update
// with the default (expectation) strategy never allocates. DDS-free.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "structloc/localisation_core/association/map_error_memory.hpp"
#include "structloc/localisation_core/expectation/expected_walls.hpp"
#include "structloc/localisation_core/expectation/visibility_cache.hpp"
#include "structloc/localisation_core/features/feature_extractor.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"
#include "structloc/localisation_core/scan/deskew.hpp"
#include "structloc/world_model/ray_cast.hpp"
#include "structloc/world_model/visibility.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::localisation_core {

struct UpdateInput {
  ScanView scan;
  geometry::Pose2D odometry_pose;  // robot base in the map frame at the scan stamp
  Eigen::Matrix3d odometry_covariance = Eigen::Matrix3d::Identity();  // of that prediction
  const BeamMotion* motion = nullptr;  // per-beam sensor motion for de-skewing, or none
};

enum class LostReason {
  kNone,
  kRejectedInput,       // the scan or prior was unusable; nothing was computed
  kNoFeatures,          // no expected feature was found in the scan
  kUnderdetermined,     // the features leave a direction of the pose open
  kCorrectionTooLarge,  // the fit would move the robot beyond the gates
  kSolverFailed,
};
const char* ToString(LostReason reason);

struct StepTimes {
  double prefilter_us = 0, expectation_us = 0, line_fit_us = 0, solve_us = 0, total_us = 0;
};  // each feature kind's own time is in FeatureKindResult::extract_us

// What one feature kind found in one scan.
struct FeatureKindResult {
  const char* kind = "";  // FeatureExtractor::Kind(), e.g. "walls"
  FeatureShape shape = FeatureShape::kPoint;
  int expected = 0;  // visible in the model at the odometric pose
  std::vector<FeatureMatch> matches;
  double extract_us = 0.0;
  int Matched() const { return static_cast<int>(matches.size()); }
};

struct LocalisationResult {
  const char* rejection = nullptr;  // why the input was rejected, or nullptr
  geometry::Pose2D pose;            // robot base, map frame (odometry when lost)
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  // x, y, theta
  bool lost = false;
  LostReason lost_reason = LostReason::kNone;
  Eigen::Vector3d weak_direction = Eigen::Vector3d::Zero();  // least determined (x, y, theta)
  double quality = 0.0;                                      // 0 .. 1, see Localiser::Update
  // One entry per enabled kind, in the order of FeatureKinds().
  std::vector<FeatureKindResult> features;
  PrefilterStats prefilter;
  StepTimes times;
  double chi2 = 0.0;
  int dof = 0;
  // What the features alone say about the robot pose (x, y, theta), at the
  // solution, before chi2_scale; zero when nothing was solved. A filter around
  // the localiser (odometry_filter.hpp) fuses the scan through it.
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  double chi2_scale = 1.0;  // max(1, chi2 / dof): the covariance's inflation for misfit

  // The entry of kind `name`, or nullptr when that kind is not enabled.
  const FeatureKindResult* Kind(const char* name) const;
  int Expected() const;  // over all kinds
  int Matched() const;
  double ExtractUs() const;  // over all kinds
};

class Localiser {
 public:
  // With the feature kinds the options enable (feature_kinds.hpp). Throws
  // std::invalid_argument when the options are invalid.
  Localiser(const world_model::WorldModel& world, const LocaliserOptions& options);
  // With the given extractors instead, run in this order (tests of a new kind).
  Localiser(const world_model::WorldModel& world, const LocaliserOptions& options,
            std::vector<std::unique_ptr<FeatureExtractor>> extractors);

  // Quality = matched / expected features, reduced when chi2/dof exceeds
  // solver.quality_chi2_per_dof; 0 when lost. The returned reference stays valid until the next
  // Update.
  const LocalisationResult& Update(const UpdateInput& input);

  // Between scans, off the path from scan to pose: computes which features
  // are visible (VisibilityCache) where the next scan will be taken (the
  // newest estimate `robot_pose` moved on as the robot moved since the last
  // call) when none computed before holds there. The update itself computes
  // a visibility only for its very first scan (or a new view); otherwise it
  // uses one that holds at its prior, else the newest one computed.
  void Anticipate(const geometry::Pose2D& robot_pose);
  // Updates that used the newest visibility although it did not hold (none
  // computed for their place yet); and visibilities computed in all.
  uint64_t StaleVisibilityUpdates() const { return stale_visibility_updates_; }
  uint64_t VisibilityComputations() const { return visibility_cache_.Computations(); }

  // The caller fused the last result into its pose (a filter around the
  // localiser): the map errors of its features are in that pose now, and the
  // next scans count them once (solver.map_error_travel_m).
  void RememberFused();

  const LocaliserOptions& Options() const { return options_; }
  const world_model::WorldModel& World() const { return world_; }

 private:
  // Chooses the visibility for a scan seen from `sensor_pose`: one that holds
  // there, else the newest one computed.
  void RefreshVisibility(const geometry::Pose2D& sensor_pose, const ScanView& scan);
  // Fades the map-error memory by the travel since the last scan and gives
  // the expected walls their factors (each point kind reads its own in Expect).
  void ApplyMapErrorMemory(const geometry::Pose2D& sensor_pose);
  void Reject(const UpdateInput& input, const char* why);
  // Steps of the pose update after the line fits, in order.
  void ExtractFeatures(const geometry::Pose2D& sensor_prior,
                       const Eigen::Matrix3d& sensor_prior_cov);
  // Sets sensor_pose / sensor_cov to the solved sensor pose, or to the prior when lost.
  void SolveAndGate(const geometry::Pose2D& sensor_prior, const Eigen::Matrix3d& sensor_prior_cov,
                    geometry::Pose2D& sensor_pose, Eigen::Matrix3d& sensor_cov);
  void CheckObservability();
  void PackMatches();
  void FinishResult(const UpdateInput& input, const geometry::Pose2D& sensor_pose,
                    const Eigen::Matrix3d& sensor_cov);

  const world_model::WorldModel& world_;
  LocaliserOptions options_;
  world_model::Scene scene_;
  std::vector<WallLineModel> lines_;
  std::vector<int> wall_line_of_;
  VisibilityCache visibility_cache_;
  int visibility_entry_ = -1;  // the cache entry the last update used
  uint64_t stale_visibility_updates_ = 0;
  std::optional<geometry::Pose2D> last_anticipated_;  // the sensor pose Anticipate last saw

  BeamDirections directions_;
  ScanPoints points_;
  std::vector<WindowLine> windows_;
  ExpectedWalls expected_;
  MapErrorMemory map_errors_;
  std::optional<geometry::Pose2D> map_errors_pose_;            // sensor pose of the last scan
  std::vector<std::unique_ptr<FeatureExtractor>> extractors_;  // from the parameter file
  Measurements measurements_;
  SolveOutput solve_;
  LocalisationResult result_;
  // Last output, the fallback when an input's own prior is unusable.
  geometry::Pose2D last_pose_;
  Eigen::Matrix3d last_covariance_ = 1e4 * Eigen::Matrix3d::Identity();
};

}  // namespace structloc::localisation_core
