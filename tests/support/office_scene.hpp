// Test and benchmark helper: the shipped office floor with its parameters, and
// a sensor pose in the hall that sees walls, corners and pillars at once.
#pragma once

#include <string>

#include "structloc/localisation_core/localiser/localiser.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "synthetic_scans.hpp"

namespace structloc::testing {

struct OfficeScene {
  world_model::WorldModel world;
  world_model::Scene scene;
  localisation_core::LocaliserOptions options;
  geometry::Pose2D truth{19.5, 6.5, 0.2};  // robot base in the east hall
  double field_of_view_rad;                // of the scans cast; the localiser reads it from them

  explicit OfficeScene(double field_of_view)
      : world(world_model::LoadWorldModel(std::string(STRUCTLOC_SOURCE_DIR) +
                                          "/maps/office_floor.xml")),
        scene(world_model::Scene::FromWorld(world)),
        options(localisation_core::LoadLocaliserOptions(std::string(STRUCTLOC_SOURCE_DIR) +
                                                        "/maps/params/office_sick.xml")),
        field_of_view_rad(field_of_view) {}

  // A noisy scan from the true sensor pose.
  SyntheticScan Scan(int beams, std::mt19937& rng) const {
    const geometry::Pose2D sensor = geometry::Compose(truth, options.sensor_mount);
    return CastScan(scene, sensor, {beams, field_of_view_rad, 30.0, 0.01}, rng);
  }

  localisation_core::UpdateInput Input(const SyntheticScan& scan) const {
    localisation_core::UpdateInput in;
    in.scan = scan.View();
    in.odometry_pose = {truth.x + 0.03, truth.y - 0.02, truth.theta + 0.01};
    in.odometry_covariance = Eigen::Vector3d(0.0025, 0.0025, 0.001).asDiagonal();
    return in;
  }
};

}  // namespace structloc::testing
