// Localiser options declared once (key, range, unit, description; the struct
// members hold the defaults), and the checks that span several options. Each
// feature kind declares its own blocks in its own file (feature_kinds.hpp).
#include "structloc/localisation_core/localiser/localiser_options.hpp"

#include <stdexcept>

#include "structloc/config/strict_xml.hpp"
#include "structloc/localisation_core/features/feature_kinds.hpp"

namespace structloc::localisation_core {

namespace {

using config::Range;
using O = LocaliserOptions;

LocaliserOptionTable PrefilterSection() {
  LocaliserOptionTable t("prefilter",
                         "step 1, thesis 3.4: range gate, unsupported points, thinning");
  t.Number("min_range_m", &O::prefilter, &PrefilterOptions::min_range_m, Range::NonNegative(), "m",
           "Table 6: readings nearer than this are dropped");
  t.Number("max_range_m", &O::prefilter, &PrefilterOptions::max_range_m, Range::Positive(), "m",
           "Table 6: readings farther than this are dropped");
  t.Number("max_neighbour_distance_m", &O::prefilter, &PrefilterOptions::max_neighbour_distance_m,
           Range::Positive(), "m",
           "Table 6: a point farther than this from both neighbours is unsupported");
  t.Number("min_neighbour_distance_m", &O::prefilter, &PrefilterOptions::min_neighbour_distance_m,
           Range::NonNegative(), "m", "Table 6: thinning distance");
  return t;
}

LocaliserOptionTable LineFitSection() {
  LocaliserOptionTable t("line_fit", "step 2, thesis 3.5.2: sliding line fits");
  t.Number("window_points", &O::line_fit, &LineFitOptions::window_points, Range::Closed(3, 100000),
           "", "Table 6: number of points in one line fit");
  t.Number("max_rms_m", &O::line_fit, &LineFitOptions::max_rms_m, Range::Positive(), "m",
           "windows scattering more than this about their line are not used");
  return t;
}

LocaliserOptionTable SolverSection() {
  LocaliserOptionTable t("solver",
                         "step 6, thesis 3.5.1/3.5.8: the pose from the matched features");
  t.Choice("mode", &O::solver, &SolverOptions::mode,
           {{"weighted", SolverMode::kWeighted},
            {"thesis_linear", SolverMode::kThesisLinear},
            {"bisection", SolverMode::kBisection}},
           "weighted Gauss-Newton, the thesis' linear system, or its bisection");
  t.Number("max_iterations", &O::solver, &SolverOptions::max_iterations,
           Range::Closed(1, LocaliserLimits::kMaxSolverIterations), "", "Gauss-Newton iterations");
  t.Number("outlier_chi2", &O::solver, &SolverOptions::outlier_chi2, Range::Positive(), "",
           "2-dof chi-square gate for a feature (13.8: 99.9 %)");
  t.Number("search_half_width_m", &O::solver, &SolverOptions::search_half_width_m,
           Range::Positive(), "m", "bisection window around odometry");
  t.Number("bisection_iterations", &O::solver, &SolverOptions::bisection_iterations,
           Range::Closed(1, LocaliserLimits::kMaxBisectionIterations), "",
           "per coordinate and sweep");
  t.Number("max_feature_std_m", &O::solver, &SolverOptions::max_feature_std_m, Range::Positive(),
           "m", "features alone must pin every direction this well, else lost");
  t.Number("max_feature_std_rad", &O::solver, &SolverOptions::max_feature_std_rad,
           Range::Positive(), "rad", "... and the heading this well");
  t.Number("quality_chi2_per_dof", &O::solver, &SolverOptions::quality_chi2_per_dof,
           Range::Positive(), "", "quality is scaled down when chi2 / dof exceeds this");
  t.Number("map_error_travel_m", &O::map_error_travel_m, Range::NonNegative(), "m",
           "a map feature's error is the same for the scans fused within about this much "
           "travel: fused again, it adds only what the scan itself measured (0: independent "
           "per scan)");
  return t;
}

LocaliserOptionTable VisibilitySection() {
  LocaliserOptionTable t("visibility",
                         "which model features are expected in the scan (its own angular range "
                         "decides the rest)");
  t.Number("min_visible_length_m", &O::visibility, &VisibilitySettings::min_visible_length_m,
           Range::NonNegative(), "m", "shorter visible wall parts are not expected");
  t.Number("max_incidence_rad", &O::visibility, &VisibilitySettings::max_incidence_rad,
           Range::LeftOpen(0, geometry::kHalfPi), "rad", "more oblique views are not expected");
  t.Number("refresh_distance_m", &O::visibility, &VisibilitySettings::refresh_distance_m,
           Range::Positive(), "m", "recompute visibility after this much travel");
  t.Number("refresh_angle_rad", &O::visibility, &VisibilitySettings::refresh_angle_rad,
           Range::Positive(), "rad", "... or rotation (scans short of a full circle only)");
  return t;
}

LocaliserOptionTable SensorMountSection() {
  LocaliserOptionTable t("sensor_mount", "laser pose on the robot (base_link -> laser)");
  t.Number("x_m", &O::sensor_mount, &geometry::Pose2D::x, Range::Any(), "m", "ahead of the base");
  t.Number("y_m", &O::sensor_mount, &geometry::Pose2D::y, Range::Any(), "m", "left of the base");
  t.Number("theta_rad", &O::sensor_mount, &geometry::Pose2D::theta, Range::Any(), "rad",
           "counter-clockwise from the base's heading");
  return t;
}

LocaliserOptionTable GatesSection() {
  LocaliserOptionTable t("gates", "limits on one update");
  t.Number("max_correction_m", &O::max_correction_m, Range::Positive(), "m",
           "larger corrections of the odometry are refused (lost)");
  t.Number("max_correction_rad", &O::max_correction_rad, Range::Positive(), "rad",
           "... and larger heading corrections");
  t.Number("max_beams", &O::max_beams, Range::Closed(1, LocaliserLimits::kMaxBeams), "",
           "buffers are sized for this many beams; longer scans are refused");
  return t;
}

}  // namespace

config::OptionFile<LocaliserOptions> LocaliserOptionFile() {
  std::vector<LocaliserOptionTable> sections = {PrefilterSection(), LineFitSection()};
  for (const auto& kind : FeatureKinds()) {
    for (auto& section : kind.sections()) sections.push_back(std::move(section));
  }
  for (auto* section : {SolverSection, VisibilitySection, SensorMountSection, GatesSection}) {
    sections.push_back(section());
  }
  // <tracking> is the tracking session's block of the same file
  // (tracking_session_options.hpp).
  return config::OptionFile<LocaliserOptions>("localisation_params", std::move(sections),
                                              {"tracking"});
}

void PrintLocaliserOptions(std::ostream& out) {
  LocaliserOptionFile().Print(out, LocaliserOptions{});
}

void LocaliserOptions::Validate() const {
  LocaliserOptionFile().Validate(*this);
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(what);
  };
  require(prefilter.max_range_m > prefilter.min_range_m,
          "prefilter: max_range_m must be > min_range_m");
  require(max_beams >= line_fit.window_points, "gates: max_beams must be >= window_points");
}

LocaliserOptions LoadLocaliserOptions(const std::string& path) {
  return LocaliserOptionFile().LoadValidated(path);
}

}  // namespace structloc::localisation_core
