// Localiser options declared once (key, range, unit, description; the struct
// members hold the defaults), and the checks that span several options.
#include "localiser_options.hpp"

#include <stdexcept>

#include "strict_xml.hpp"

namespace structloc::localisation {

namespace {

using config::OptionTable;
using config::Range;
using O = LocaliserOptions;

constexpr double kHalfPi = geometry::kPi / 2;

OptionTable<O> PrefilterSection() {
  OptionTable<O> t("prefilter", "step 1, thesis 3.4: range gate, unsupported points, thinning");
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

OptionTable<O> LineFitSection() {
  OptionTable<O> t("line_fit", "step 2, thesis 3.5.2: sliding line fits");
  t.Number("window_points", &O::line_fit, &LineFitOptions::window_points, Range::Closed(3, 100000),
           "", "Table 6: number of points in one line fit");
  t.Number("max_rms_m", &O::line_fit, &LineFitOptions::max_rms_m, Range::Positive(), "m",
           "windows scattering more than this about their line are not used");
  return t;
}

OptionTable<O> WallsSection() {
  OptionTable<O> t("walls", "feature kind walls, thesis 3.5.3: window lines clustered per wall");
  t.Choice("strategy", &O::wall_strategy,
           {{"expectation", WallStrategy::kExpectation}, {"kohonen", WallStrategy::kKohonen}},
           "nearest expected wall within the gates, or the thesis' Kohonen map (see <kohonen>)");
  t.Number("gate_r_m", &O::walls, &WallClusterOptions::gate_r_m, Range::Positive(), "m",
           "Table 6: size of cluster (r)");
  t.Number("gate_alpha_rad", &O::walls, &WallClusterOptions::gate_alpha_rad,
           Range::Open(0, kHalfPi), "rad", "Table 6: size of cluster (alpha)");
  t.Number("min_cluster_size", &O::walls, &WallClusterOptions::min_cluster_size, Range::AtLeast(1),
           "", "Table 6: minimum number of window lines in a cluster");
  t.Number("extent_margin_m", &O::walls, &WallClusterOptions::extent_margin_m, Range::Any(), "m",
           "a window must lie within the visible wall plus this (<= 0 disables the check)");
  t.Number("min_point_sigma_m", &O::walls, &WallClusterOptions::min_point_sigma_m,
           Range::Positive(), "m", "floor of the per-point noise used for covariances");
  return t;
}

OptionTable<O> KohonenSection() {
  OptionTable<O> t("kohonen", "walls strategy kohonen, thesis 3.5.3 EQ 21-22");
  t.Number("iterations", &O::kohonen, &KohonenOptions::iterations,
           Range::Closed(1, LocaliserLimits::kMaxKohonenIterations), "", "training steps per scan");
  t.Number("initial_learning_rate", &O::kohonen, &KohonenOptions::initial_learning_rate,
           Range::LeftOpen(0, 1), "", "eta(0), decreasing linearly to 0");
  t.Number("initial_neighbourhood", &O::kohonen, &KohonenOptions::initial_neighbourhood,
           Range::NonNegative(), "", "sigma(0) in neuron-index units, shrinking to 0");
  t.Number("seed", &O::kohonen_seed, Range::Any(), "", "seeds the Kohonen strategy's generator");
  return t;
}

OptionTable<O> CornersSection() {
  OptionTable<O> t("corners", "feature kind corners, thesis 3.5.4 EQ 31: window-line crossings");
  t.Flag("enabled", &O::use_corners, "extract and use corners");
  t.Number("next_windows", &O::corners, &CornerOptions::next_windows, Range::AtLeast(1), "",
           "k: windows after window i intersected with it");
  t.Number("angle_tolerance_rad", &O::corners, &CornerOptions::angle_tolerance_rad,
           Range::Open(0, kHalfPi), "rad", "lines must meet at pi/2 within this");
  t.Number("gate_m", &O::corners, &CornerOptions::gate_m, Range::Positive(), "m",
           "distance gate around an expected corner");
  t.Number("min_cluster_size", &O::corners, &CornerOptions::min_cluster_size, Range::AtLeast(1), "",
           "minimum number of crossings in a cluster");
  t.Number("min_point_sigma_m", &O::corners, &CornerOptions::min_point_sigma_m, Range::Positive(),
           "m", "floor of a corner's standard deviation");
  t.Number("redundant_wall_distance_m", &O::corners, &CornerOptions::redundant_wall_distance_m,
           Range::Positive(), "m", "a matched wall passes through a corner within this");
  t.Number("redundant_min_sin", &O::corners, &CornerOptions::redundant_min_sin, Range::Closed(0, 1),
           "", "two such walls at an angle with a larger sine make the corner redundant");
  return t;
}

OptionTable<O> CylindersSection() {
  OptionTable<O> t("cylinders", "feature kind cylinders, thesis 3.5.6 EQ 36-40: circle fits");
  t.Flag("enabled", &O::use_cylinders, "extract and use cylinders");
  t.Number("candidate_gate_m", &O::cylinders, &CylinderOptions::candidate_gate_m, Range::Positive(),
           "m", "window centroid to expected surface");
  t.Number("radius_tolerance_m", &O::cylinders, &CylinderOptions::radius_tolerance_m,
           Range::Positive(), "m", "|fitted radius - model radius|");
  t.Number("min_quality", &O::cylinders, &CylinderOptions::min_quality, Range::NonNegative(),
           "1/m^4", "EQ 40 threshold on Q = 1 / sum(residual^2)");
  t.Number("gate_m", &O::cylinders, &CylinderOptions::gate_m, Range::Positive(), "m",
           "fitted centre to expected centre");
  t.Number("min_cluster_size", &O::cylinders, &CylinderOptions::min_cluster_size, Range::AtLeast(1),
           "", "minimum number of circle fits in a cluster");
  t.Number("min_point_sigma_m", &O::cylinders, &CylinderOptions::min_point_sigma_m,
           Range::Positive(), "m", "floor of the per-point noise for the covariance");
  return t;
}

OptionTable<O> SolverSection() {
  OptionTable<O> t("solver", "step 6, thesis 3.5.1/3.5.8: the pose from the matched features");
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
  return t;
}

OptionTable<O> VisibilitySection() {
  OptionTable<O> t("visibility", "which model features are expected in the scan");
  t.Number("field_of_view_rad", &O::visibility, &VisibilitySettings::field_of_view_rad,
           Range::LeftOpen(0, 2 * geometry::kPi + 1e-9), "rad", "the scanner's field of view");
  t.Number("min_visible_length_m", &O::visibility, &VisibilitySettings::min_visible_length_m,
           Range::NonNegative(), "m", "shorter visible wall parts are not expected");
  t.Number("max_incidence_rad", &O::visibility, &VisibilitySettings::max_incidence_rad,
           Range::LeftOpen(0, kHalfPi), "rad", "more oblique views are not expected");
  t.Number("refresh_distance_m", &O::visibility, &VisibilitySettings::refresh_distance_m,
           Range::Positive(), "m", "recompute visibility after this much travel");
  t.Number("refresh_angle_rad", &O::visibility, &VisibilitySettings::refresh_angle_rad,
           Range::Positive(), "rad", "... or rotation (limited fields of view only)");
  return t;
}

OptionTable<O> SensorMountSection() {
  OptionTable<O> t("sensor_mount", "laser pose on the robot (base_link -> laser)");
  t.Number("x_m", &O::sensor_mount, &geometry::Pose2D::x, Range::Any(), "m", "ahead of the base");
  t.Number("y_m", &O::sensor_mount, &geometry::Pose2D::y, Range::Any(), "m", "left of the base");
  t.Number("theta_rad", &O::sensor_mount, &geometry::Pose2D::theta, Range::Any(), "rad",
           "counter-clockwise from the base's heading");
  return t;
}

OptionTable<O> GatesSection() {
  OptionTable<O> t("gates", "limits on one update");
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
  return config::OptionFile<LocaliserOptions>(
      "localisation_params",
      {PrefilterSection(), LineFitSection(), WallsSection(), KohonenSection(), CornersSection(),
       CylindersSection(), SolverSection(), VisibilitySection(), SensorMountSection(),
       GatesSection()});
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
  const auto file = config::XmlFile::Load(path);
  const auto o = LocaliserOptionFile().Load(file);
  try {
    o.Validate();
  } catch (const std::invalid_argument& e) {
    file.Fail(file.Root(), e.what());
  }
  return o;
}

}  // namespace structloc::localisation
