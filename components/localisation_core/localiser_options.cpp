// Localiser options: validation and XML loading.
#include "localiser_options.hpp"

#include <stdexcept>

#include "strict_xml.hpp"

namespace structloc::localisation {

void LocaliserOptions::Validate() const {
  prefilter.Validate();
  line_fit.Validate();
  walls.Validate();
  kohonen.Validate();
  corners.Validate();
  cylinders.Validate();
  solver.Validate();
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(what);
  };
  require(visibility.field_of_view_rad > 0.0 &&
              visibility.field_of_view_rad <= 2 * geometry::kPi + 1e-9,
          "visibility: field_of_view_rad must be in (0, 2 pi]");
  require(visibility.min_visible_length_m >= 0.0, "visibility: min_visible_length_m must be >= 0");
  require(visibility.max_incidence_rad > 0.0 && visibility.max_incidence_rad <= geometry::kPi / 2,
          "visibility: max_incidence_rad must be in (0, pi/2]");
  require(visibility.refresh_distance_m > 0.0, "visibility: refresh_distance_m must be > 0");
  require(visibility.refresh_angle_rad > 0.0, "visibility: refresh_angle_rad must be > 0");
  require(geometry::IsFinite(sensor_mount), "sensor_mount: must be finite");
  require(max_correction_m > 0.0, "gates: max_correction_m must be > 0");
  require(max_correction_rad > 0.0, "gates: max_correction_rad must be > 0");
  require(max_beams >= line_fit.window_points, "gates: max_beams must be >= window_points");
  require(max_beams <= LocaliserLimits::kMaxBeams, "gates: max_beams must be <= 1000000");
  require(solver.bisection_iterations <= LocaliserLimits::kMaxBisectionIterations,
          "solver: bisection_iterations must be <= 60");
  require(solver.max_iterations <= LocaliserLimits::kMaxSolverIterations,
          "solver: max_iterations must be <= 1000");
  require(kohonen.iterations <= LocaliserLimits::kMaxKohonenIterations,
          "kohonen: iterations must be <= 100000");
}

namespace {

using config::AttributeReader;
using config::XmlFile;

const tinyxml2::XMLElement& Section(const XmlFile& file, const tinyxml2::XMLElement& root,
                                    const char* name) {
  const auto* e = root.FirstChildElement(name);
  if (e == nullptr) file.Fail(root, std::string("missing section <") + name + ">");
  if (const auto* second = e->NextSiblingElement(name)) {
    file.Fail(*second, std::string("a second <") + name + "> section; write each section once");
  }
  return *e;
}

}  // namespace

LocaliserOptions LoadLocaliserOptions(const std::string& path) {
  const auto file = XmlFile::Load(path);
  const auto& root = file.Root("localisation_params");
  config::RequireChildNames(file, root,
                            {"prefilter", "line_fit", "walls", "kohonen", "corners", "cylinders",
                             "solver", "visibility", "sensor_mount", "gates", "tracking"});
  LocaliserOptions o;
  {
    AttributeReader a(file, Section(file, root, "prefilter"));
    o.prefilter.min_range_m = a.Double("min_range_m");
    o.prefilter.max_range_m = a.Double("max_range_m");
    o.prefilter.max_neighbour_distance_m = a.Double("max_neighbour_distance_m");
    o.prefilter.min_neighbour_distance_m = a.Double("min_neighbour_distance_m");
    a.Finish();
  }
  {
    AttributeReader a(file, Section(file, root, "line_fit"));
    o.line_fit.window_points = a.IntegerIn<int>("window_points", 3, 100000);
    o.line_fit.max_rms_m = a.Double("max_rms_m");
    a.Finish();
  }
  {
    AttributeReader a(file, Section(file, root, "walls"));
    const std::string strategy = a.String("strategy");
    if (strategy == "expectation") {
      o.wall_strategy = WallStrategy::kExpectation;
    } else if (strategy == "kohonen") {
      o.wall_strategy = WallStrategy::kKohonen;
    } else {
      a.Fail("strategy must be expectation or kohonen, not '" + strategy + "'");
    }
    o.walls.gate_r_m = a.Double("gate_r_m");
    o.walls.gate_alpha_rad = a.Double("gate_alpha_rad");
    o.walls.min_cluster_size = a.IntegerIn<int>("min_cluster_size");
    o.walls.extent_margin_m = a.Double("extent_margin_m");
    o.walls.min_point_sigma_m = a.Double("min_point_sigma_m");
    a.Finish();
  }
  {
    AttributeReader a(file, Section(file, root, "kohonen"));
    o.kohonen.iterations =
        a.IntegerIn<int>("iterations", 1, LocaliserLimits::kMaxKohonenIterations);
    o.kohonen.initial_learning_rate = a.Double("initial_learning_rate");
    o.kohonen.initial_neighbourhood = a.Double("initial_neighbourhood");
    o.kohonen_seed = a.IntegerIn<uint32_t>("seed");
    a.Finish();
  }
  {
    AttributeReader a(file, Section(file, root, "corners"));
    o.use_corners = a.Bool("enabled");
    o.corners.next_windows = a.IntegerIn<int>("next_windows");
    o.corners.angle_tolerance_rad = a.Double("angle_tolerance_rad");
    o.corners.gate_m = a.Double("gate_m");
    o.corners.min_cluster_size = a.IntegerIn<int>("min_cluster_size");
    o.corners.min_point_sigma_m = a.Double("min_point_sigma_m");
    a.Finish();
  }
  {
    AttributeReader a(file, Section(file, root, "cylinders"));
    o.use_cylinders = a.Bool("enabled");
    o.cylinders.candidate_gate_m = a.Double("candidate_gate_m");
    o.cylinders.radius_tolerance_m = a.Double("radius_tolerance_m");
    o.cylinders.min_quality = a.Double("min_quality");
    o.cylinders.gate_m = a.Double("gate_m");
    o.cylinders.min_cluster_size = a.IntegerIn<int>("min_cluster_size");
    o.cylinders.min_point_sigma_m = a.Double("min_point_sigma_m");
    a.Finish();
  }
  {
    AttributeReader a(file, Section(file, root, "solver"));
    const std::string mode = a.String("mode");
    if (mode == "weighted") {
      o.solver.mode = SolverMode::kWeighted;
    } else if (mode == "thesis_linear") {
      o.solver.mode = SolverMode::kThesisLinear;
    } else if (mode == "bisection") {
      o.solver.mode = SolverMode::kBisection;
    } else {
      a.Fail("mode must be weighted, thesis_linear or bisection, not '" + mode + "'");
    }
    o.solver.max_iterations =
        a.IntegerIn<int>("max_iterations", 1, LocaliserLimits::kMaxSolverIterations);
    o.solver.outlier_chi2 = a.Double("outlier_chi2");
    o.solver.search_half_width_m = a.Double("search_half_width_m");
    o.solver.bisection_iterations =
        a.IntegerIn<int>("bisection_iterations", 1, LocaliserLimits::kMaxBisectionIterations);
    o.solver.max_feature_std_m = a.Double("max_feature_std_m");
    o.solver.max_feature_std_rad = a.Double("max_feature_std_rad");
    a.Finish();
  }
  {
    AttributeReader a(file, Section(file, root, "visibility"));
    o.visibility.field_of_view_rad = a.Double("field_of_view_rad");
    o.visibility.min_visible_length_m = a.Double("min_visible_length_m");
    o.visibility.max_incidence_rad = a.Double("max_incidence_rad");
    o.visibility.refresh_distance_m = a.Double("refresh_distance_m");
    o.visibility.refresh_angle_rad = a.Double("refresh_angle_rad");
    a.Finish();
  }
  {
    AttributeReader a(file, Section(file, root, "sensor_mount"));
    o.sensor_mount = {a.Double("x_m"), a.Double("y_m"), a.Double("theta_rad")};
    a.Finish();
  }
  {
    const auto& gates = Section(file, root, "gates");
    AttributeReader a(file, gates);
    o.max_correction_m = a.Double("max_correction_m");
    o.max_correction_rad = a.Double("max_correction_rad");
    o.max_beams = a.IntegerIn<int>("max_beams", 1, LocaliserLimits::kMaxBeams);
    a.Finish();
  }
  try {
    o.Validate();
  } catch (const std::invalid_argument& e) {
    file.Fail(root, e.what());
  }
  return o;
}

}  // namespace structloc::localisation
