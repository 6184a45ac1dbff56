// The seam for feature kinds (thesis 3.5.3-3.5.6): every kind of landmark the
// localiser matches (walls, corners, cylinders, ...) is one FeatureExtractor.
// It places the map's features of its kind that the scan should see, then sees
// the sliding line fits of the scan and hands back solver measurements with
// their covariance and one typed match per feature found. The localiser runs
// the enabled extractors in the fixed order of FeatureKinds() (walls first),
// solves once over all measurements and reports per kind, so that results,
// messages and timings need no change for a new kind.
#pragma once

#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/localisation_core/association/map_error_memory.hpp"
#include "structloc/localisation_core/expectation/expected_walls.hpp"
#include "structloc/localisation_core/scan/line_fit.hpp"
#include "structloc/localisation_core/scan/scan_points.hpp"
#include "structloc/localisation_core/solver/pose_solver.hpp"
#include "structloc/world_model/visibility.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::localisation_core {

// What a kind is measured as: a line (r, alpha) or a point (x, y).
enum class FeatureShape { kLine, kPoint };

// One matched feature, in the sensor frame. Lines fill r_m and alpha_rad,
// points x_m, y_m and radius_m (0 for a corner).
struct FeatureMatch {
  int model_id = 0;
  int members = 0;  // window lines, line crossings or circle fits in the cluster
  double r_m = 0.0;
  double alpha_rad = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double radius_m = 0.0;
  double residual_m = 0.0;  // of the solved pose
  bool used = false;        // taken into the pose solve
  int row = 0;              // index of its measurement in Measurements::lines or ::points
  int slot = -1;            // the map feature's slot in the MapErrorMemory (-1: none)
};

// The solver's input from all kinds of one scan.
struct Measurements {
  std::vector<WallMeasurement> lines;
  std::vector<PointMeasurement> points;
  void Clear() {
    lines.clear();
    points.clear();
  }
};

// What an extractor sees of the map for one scan.
struct ExpectationInput {
  const world_model::WorldModel* map = nullptr;
  const world_model::Visibility* visibility = nullptr;  // from the odometric sensor pose
  const ExpectedWalls* walls = nullptr;                 // the expected walls, sensor frame
  geometry::Pose2D sensor_prior;                        // odometric sensor pose
  const MapErrorMemory* map_errors = nullptr;           // each slot's map-error scale
};

// What an extractor sees of one scan.
struct ExtractionInput {
  const ExpectedWalls* expected = nullptr;           // the expected walls, sensor frame
  const std::vector<WindowLine>* windows = nullptr;  // sliding line fits (step 2)
  const ScanPoints* points = nullptr;                // prefiltered points, sensor frame
  geometry::Pose2D sensor_prior;                     // odometric sensor pose
  Eigen::Matrix3d sensor_prior_covariance = Eigen::Matrix3d::Identity();  // of that pose
  int window_points = 0;                                                  // points per window line
  bool thesis_values = false;  // measure with the thesis' means, not the refined fits
};

class FeatureExtractor {
 public:
  virtual ~FeatureExtractor() = default;
  // The kind's name: its section in the parameter file and its name in
  // results, messages and timings.
  virtual const char* Kind() const = 0;
  virtual FeatureShape Shape() const = 0;
  // Called once, when the localiser is built: this kind's features of `map`
  // take the slots first_slot, first_slot + 1, ... of the MapErrorMemory
  // (their map error counted once over nearby scans); returns how many. The
  // walls' slots are their wall lines, which the localiser numbers first.
  virtual int TakeSlots(const world_model::WorldModel& map, int first_slot) = 0;
  // Places this kind's features that the map lets this scan see, before
  // Extract. Must not allocate once the buffers sized at construction suffice.
  virtual void Expect(const ExpectationInput& in) = 0;
  // How many features of this kind the model expects in this scan.
  virtual int Expected() const = 0;
  // Finds this kind's features in the scan, appends one measurement with its
  // covariance per feature found to `all` and one match to `matches`. The
  // measurements of the extractors that ran before are in `all` already (the
  // corners' redundancy rule reads the walls'). Must not allocate once the
  // buffers sized at construction suffice.
  virtual void Extract(const ExtractionInput& in, Measurements& all,
                       std::vector<FeatureMatch>& matches) = 0;
};

}  // namespace structloc::localisation_core
