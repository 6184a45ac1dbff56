// All parameters of the localisation pipeline: one options struct per step
// with the thesis' Table 6 values as defaults (other defaults documented where
// they are declared). Every option is declared once, in LocaliserOptionFile()
// (XML key with unit, range, description); loading an XML parameter file (every
// key present, none unknown), validation and the `structloc params` listing
// derive from that declaration.
#pragma once

#include <ostream>
#include <string>

#include "structloc/config/option_table.hpp"
#include "structloc/geometry/pose2d.hpp"
#include "structloc/localisation_core/features/feature_kind_options.hpp"
#include "structloc/localisation_core/scan/line_fit.hpp"
#include "structloc/localisation_core/scan/prefilter.hpp"
#include "structloc/localisation_core/solver/pose_solver.hpp"

namespace structloc::localisation_core {

// Which model features are expected in a scan. The scan's own angular range
// (ScanView) and the prefilter's range limits decide the rest
// (scan_visibility.hpp); there is no field-of-view option.
struct VisibilitySettings {
  double min_visible_length_m = 0.3;  // shorter visible wall parts are not expected
  double max_incidence_rad = 1.309;   // 75 deg: more oblique views are not expected
  double refresh_distance_m = 0.25;   // recompute visibility after this much travel
  double refresh_angle_rad = 0.2;     // ... or rotation (scans short of a full circle only)
};

// Upper bounds on the work one scan may cost, so that a typo such as
// bisection_iterations="2000000000" is refused instead of hanging the replay.
struct LocaliserLimits {
  // Each bisection step halves the search interval: 60 steps take 0.2 m below
  // double resolution.
  static constexpr int kMaxBisectionIterations = 60;
  static constexpr int kMaxSolverIterations = 1000;  // Gauss-Newton steps per scan
  static constexpr int kMaxBeams = 1000000;          // buffers are sized for max_beams
};

struct LocaliserOptions {
  PrefilterOptions prefilter;
  LineFitOptions line_fit;
  // Each feature kind's options (walls, corners, cylinders, ...), of the
  // types its own folder declares: kinds.Get<CornerKindOptions>().
  FeatureKindOptions kinds;
  SolverOptions solver;
  VisibilitySettings visibility;
  geometry::Pose2D sensor_mount;  // laser pose on the robot (base_link -> laser)
  // A map feature's error counts as one error for the scans fused within
  // about this much travel (map_error_memory.hpp); 0: independent per scan.
  double map_error_travel_m = 0.0;
  double max_correction_m = 0.5;  // larger corrections of the odometry are refused
  double max_correction_rad = 0.35;
  int max_beams = 4096;  // buffers are sized for this many beams

  // Throws std::invalid_argument naming the broken option ("walls: gate_r_m ...").
  void Validate() const;
};

// The declaration of every option: one <section> per pipeline step and feature
// kind, each key with its range, unit and description.
config::OptionFile<LocaliserOptions> LocaliserOptionFile();

// Lists every key with its default, unit, valid values and meaning.
void PrintLocaliserOptions(std::ostream& out);

// Reads a <localisation_params> file (see maps/params/*.xml). Throws
// config::ConfigError naming file, line and problem, including invalid values.
LocaliserOptions LoadLocaliserOptions(const std::string& path);

// The table the localiser's parameter file is declared in; each feature kind
// declares its own blocks with it (see feature_kinds.hpp).
using LocaliserOptionTable = config::OptionTable<LocaliserOptions>;

}  // namespace structloc::localisation_core
